#include "control/channel/block_search.hpp"

#include <cmath>

namespace vmt::control::channel {

bool SteersBlockSearch(nc::HashCommand command) {
  return command == nc::HashCommand::kDistanceProgStart ||
         command == nc::HashCommand::kBlockSearch || command == nc::HashCommand::kCaxTrack;
}

std::string RefusedHashCommand(nc::HashCommand command) {
  if (command == nc::HashCommand::kVectorOffset)
    return "#VECTOR OFFSET (path-dependent angle correction, block search 4.2.3) is not "
           "supported by vmt (docs/conformance.md): it has no tool orientation angles (ANC, DRC) "
           "to offset";
  return "";
}

std::string CheckBlockSearch(const BlockSearchParameters& p) {
  switch (p.type) {
    case BlockSearchType::kNone:
    case BlockSearchType::kFileOffset:
    case BlockSearchType::kBlockCounter:
    case BlockSearchType::kBlockNumber:
    case BlockSearchType::kProgramEnd:
    case BlockSearchType::kBreakpointOnly:
      break;
    default:
      return "mc_cmd_bs_type_w " + std::to_string(static_cast<int>(p.type)) +
             ": the types are 0 (none), 1 (file offset), 3 (block counter), 4 (block number), "
             "5 (program end) and 6 (breakpoint only); type 2 no longer exists";
  }
  if (p.deviation_max < 0) return "mc_cmd_bs_deviation_max_w must not be negative";
  if (p.file_offset < 0) return "mc_command_file_offset_w must not be negative";
  if (!(p.covered_distance >= 0 && p.covered_distance <= 1000))
    return "mc_cmd_bs_covered_distance_w must lie in 0.0 .. 1000.0 per mille";
  if (!(p.distance_prog_start >= 0) || !std::isfinite(p.distance_prog_start))
    return "mc_cmd_bs_distance_prog_start_w must not be negative";
  if (!(p.breakpoint_position >= 0) || !std::isfinite(p.breakpoint_position))
    return "mc_cmd_bs_breakpoint_position_w must not be negative";
  auto file = [](const FilePosition& f, const char* what) -> std::string {
    if (f.offset < -1 || f.offset > INT32_MAX)
      return std::string("mc_cmd_bs_pos_") + what + "_offset_w must lie in 0 .. MAX_SGN32";
    if (f.path != 0 && f.path != 1)
      return std::string("mc_cmd_bs_pos_") + what + "_type_w: 0 (main program path) or 1 (subprogram path)";
    if (f.count < 1 || f.count > INT16_MAX)
      return std::string("mc_cmd_bs_pos_") + what + "_count_w must lie in 1 .. MAX_SGN16";
    if (f.name.size() > 83)
      return std::string("mc_cmd_bs_pos_") + what + "_name_w: at most 84 characters";
    return "";
  };
  if (p.type == BlockSearchType::kFileOffset) {
    if (p.start.offset < 0) return "block search type 1 needs mc_cmd_bs_pos_start_offset_w";
    if (auto e = file(p.start, "start"); !e.empty()) return e;
    if (p.end.offset >= 0)
      if (auto e = file(p.end, "end"); !e.empty()) return e;
  }
  if (p.type == BlockSearchType::kBlockCounter && p.intern_block_count < 1)
    return "block search type 3 needs mc_cmd_bs_intern_block_count_w >= 1";
  if (p.block_nbr_prog_name.size() > 83)
    return "mc_cmd_bs_block_nbr_prog_name_w: at most 84 characters";
  return "";
}

const char* ToString(BlockSearchState s) {
  switch (s) {
    case BlockSearchState::kInactive:
      return "HLI_BS_INACTIVE";
    case BlockSearchState::kWaitForPlcOn:
      return "HLI_BS_WAIT_FOR_PLC_ON";
    case BlockSearchState::kActive:
      return "HLI_BS_ACTIVE";
    case BlockSearchState::kWaitForPlcOff:
      return "HLI_BS_WAIT_FOR_PLC_OFF";
    case BlockSearchState::kWaitReturnToContour:
      return "HLI_BS_WAIT_RETURN_TO_CONTOUR";
    case BlockSearchState::kReturningToContour:
      return "HLI_BS_RETURNING_TO_CONTOUR";
    case BlockSearchState::kWaitForContinueContour:
      return "HLI_BS_WAIT_FOR_CONTINUE_CONTOUR";
  }
  return "?";
}

namespace {

/// The file as started: the full name, or its trailing path components (the scene names
/// programs relative to itself, the PLC may give the name alone).
bool SameFile(const std::string& wanted, const std::string& file) {
  if (wanted == file) return true;
  return file.size() > wanted.size() && file.ends_with(wanted) &&
         file[file.size() - wanted.size() - 1] == '/';
}

std::string Upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

bool ContinueMatcher::AtFilePosition(const FilePosition& f, const nc::PreparedBlock& block,
                                     const nc::Program& program, uint32_t program_index) {
  if (block.block < 0) return false;
  const nc::SourcePos& pos = program.blocks[static_cast<size_t>(block.block)].pos;
  if (pos.offset != f.offset) return false;
  if ((f.path == 1) != (program_index != 0)) return false;
  return f.name.empty() ? program_index == 0 : SameFile(f.name, program.files[pos.file]);
}

bool ContinueMatcher::Matches(const nc::PreparedBlock& block, const nc::Program& program,
                              uint32_t program_index) {
  if (block.block < 0) return false;
  switch (p_.type) {
    case BlockSearchType::kFileOffset:
      return AtFilePosition(p_.start, block, program, program_index) && ++passes_ >= p_.start.count;
    case BlockSearchType::kBlockCounter:
      // The count runs on over lines that hand out no block (comments, blank lines): the
      // first block at or beyond it continues.
      return block.block_count >= p_.intern_block_count;
    case BlockSearchType::kBlockNumber: {
      const int32_t number = program.blocks[static_cast<size_t>(block.block)].number;
      if (number < 0 || static_cast<uint32_t>(number) != p_.block_number) return false;
      // Section 10: a pass count below 2 takes the first occurrence.
      if (!p_.block_nbr_prog_name.empty()) {
        std::string name = p_.block_nbr_prog_name;
        if (!name.empty() && name[0] == '%') name.erase(0, 1);
        if (Upper(name) != Upper(program.name)) return false;
      }
      return ++passes_ >= static_cast<int64_t>(p_.block_number_pass);
    }
    default:
      return false;
  }
}

bool ContinueMatcher::EndMatches(const nc::PreparedBlock& block, const nc::Program& program,
                                 uint32_t program_index) {
  if (p_.type != BlockSearchType::kFileOffset || p_.end.offset < 0) return false;
  return AtFilePosition(p_.end, block, program, program_index) && ++end_passes_ >= p_.end.count;
}

double DistanceOf(const BlockMotion& motion, const std::vector<axes::AxisParameters>& axes) {
  if (!motion.moves) return 0;
  auto main_axis = [&](size_t a) {
    const std::string& n = axes[a].name;
    return n == "X" || n == "Y" || n == "Z";
  };
  const bool arc = motion.arc_axes[0] >= 0;
  double linear2 = 0;
  for (size_t a = 0; a < axes.size() && a < motion.start.size(); ++a) {
    if (!main_axis(a)) continue;
    if (arc && (static_cast<int>(a) == motion.arc_axes[0] || static_cast<int>(a) == motion.arc_axes[1]))
      continue;
    const double d = motion.end[a] - motion.start[a];
    linear2 += d * d;
  }
  double along = 0;
  if (arc && main_axis(static_cast<size_t>(motion.arc_axes[0])) &&
      main_axis(static_cast<size_t>(motion.arc_axes[1])))
    along = std::abs(motion.arc_sweep) * motion.arc_radius;
  const double main = std::sqrt(along * along + linear2);
  if (main > 0) return main;
  // No main axis moves: the following axis at its dynamic limit, the one taking longest.
  double longest = 0, travel = 0;
  for (size_t a = 0; a < axes.size() && a < motion.start.size(); ++a) {
    const double d = std::abs(motion.end[a] - motion.start[a]);
    const double time = axes[a].rapid_per_s > 0 ? d / axes[a].rapid_per_s : d;
    if (time > longest) longest = time, travel = d;
  }
  return travel;
}

}  // namespace vmt::control::channel
