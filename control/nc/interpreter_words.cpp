// The interpreter's words: the addresses of a block (G codes, axes, F, I/J/K, M/S/T/D/H/Q,
// R and RX/RY/RZ) into the modal state and the PreparedBlock, with the lead of G33/G63/G64
// and the fictive axes X1/Y1 of the coordinate transformations.
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "control/nc/interpreter.hpp"
// Pure geometry without the channel: the fictive words are converted here, so that the
// program's position, incremental words and block search know X and C.
#include "control/nc/coordinate_transformation.hpp"
#include "control/nc/modal_g_codes.hpp"

namespace vmt::control::nc {

int Interpreter::AxisOf(uint32_t address) {
  std::vector<int8_t>& cache = axis_cache_[current_];
  if (cache.size() <= address) cache.resize(address + 1, -2);
  int8_t& axis = cache[address];
  if (axis == -2) {
    axis = -1;
    const std::string& name = program().symbols.Name(address);
    for (size_t a = 0; a < config_.axes.size(); ++a)
      if (config_.axes[a] == name) axis = static_cast<int8_t>(a);
  }
  return axis;
}

bool Interpreter::Lead(Dialect dialect, std::optional<double> f_word, uint32_t f_offset,
                       uint8_t ijk, const uint32_t ijk_offset[3], uint32_t block_offset,
                       PreparedBlock& out) {
  // vmt's reading (the manuals give no syntax): MTC200 programs the lead of G33/G63/G64 as F
  // in mm per revolution, ISG as K; the feed of G94/G95 stays for later G01 blocks. ISG's F
  // in such a block is its feed, kept for after the thread.
  const bool isg = dialect == Dialect::kIsg;
  const char* name = isg ? "K" : "F";
  for (int k = 0; k < 3; ++k) {
    if (!(ijk >> k & 1) || (isg && k == 2)) continue;
    return Fail(ijk_offset[k], std::string(1, static_cast<char>('I' + k)) +
                                   " in G33/G63/G64: the lead is " + name + " (mm per revolution)");
  }
  std::optional<double> lead;
  uint32_t lead_offset = 0;
  if (isg) {
    if (f_word) modal_.feed = *f_word;
    if (ijk & 4) lead = out.centre[2], lead_offset = ijk_offset[2];
    out.centre[2] = 0;
    out.has_centre = false;
  } else if (f_word) {
    lead = f_word, lead_offset = f_offset;
  }
  if (lead) {
    if (!(*lead > 0))
      return Fail(lead_offset, std::string("lead ") + name + " " + std::to_string(*lead) +
                                   " of G33/G63/G64 must be > 0 mm per revolution");
    modal_.lead = *lead;
  }
  const bool moves = out.programmed && !out.homing && !out.set_position && !out.repos;
  if (moves && !(modal_.lead > 0))
    return Fail(block_offset, std::string("G33/G63/G64 without a lead: program ") + name +
                                  " (mm per revolution)");
  return true;
}

bool Interpreter::GWord(double v, uint32_t offset, PreparedBlock& out) {
  const int g = static_cast<int>(std::lround(v));
  if (std::abs(v - g) > 1e-9) return Fail(offset, "G" + std::to_string(v) + " is not a G code");
  switch (g) {
    case 0:
      modal_.motion = Motion::kRapid;
      break;
    case 1:
      modal_.motion = Motion::kLinear;
      break;
    case 2:
      modal_.motion = Motion::kArcCw;
      break;
    case 3:
      modal_.motion = Motion::kArcCcw;
      break;
    case 33:
      modal_.motion = Motion::kThread;
      break;
    case 63:
      modal_.motion = Motion::kTapping;
      break;
    case 64:
      modal_.motion = Motion::kRigidTapping;
      break;
    case 4:
      out.dwell_s = -1;
      break;  // the dwell time follows as F or X
    case 31:
    case 32: {
      const int x = NamedAxis("X"), c = NamedAxis("C");
      if (x < 0 || c < 0)
        return Fail(offset, "G" + std::to_string(g) +
                                " (coordinate transformation) needs the axes X and C in "
                                "this channel");
      // G32 unrolls the cylinder at the radius X has now (before the block's moves).
      if (g == 32 && modal_.transformation != Transformation::kCylinder) {
        if (!(std::abs(position_[x]) >= 1e-3))
          return Fail(offset, "G32 (cylinder surface transformation) at X " +
                                  std::to_string(position_[x]) +
                                  ": the cylinder needs a radius; position X first");
        modal_.cylinder_radius = std::abs(position_[x]);
      }
      modal_.transformation = static_cast<Transformation>(g);
      break;
    }
    case 74:
      out.homing = true;
      break;
    case 77:
      out.repos = true;
      break;
    case 92:
      out.set_position = true;
      break;
    case 100:
      out.measuring = true;
      break;
    default:
      if (!SetModalG(g, modal_)) return Fail(offset, "G" + std::to_string(g) + " is not supported");
  }
  return true;
}

bool Interpreter::AuxWord(char letter, int index, double v, PreparedBlock& out) {
  switch (letter) {
    case 'M': {
      const int m = static_cast<int>(std::lround(v));
      // Mj= with j >= 2 addresses spindle j (channel further_spindles.hpp), never the
      // main spindle's, the coolant's or the program's functions.
      const bool own = index <= 1;
      if (own && (m == 3 || m == 4 || m == 5 || m == 19)) modal_.spindle = m;
      if (own && (m == 7 || m == 8 || m == 9)) modal_.coolant = m;
      if (own && (m == 30 || m == 2)) out.end = true;
      out.aux.push_back({'M', index, v});
      return true;
    }
    case 'S':
      // S and S1= are the main spindle's speed; Sj= with j >= 2 spindle j's.
      if (index <= 1 && !out.repos) modal_.spindle_speed = v;
      out.aux.push_back({'S', index, v});
      return true;
    case 'T':
      modal_.tool = static_cast<int>(v);
      out.aux.push_back({'T', index, v});
      return true;
    case 'D':
      modal_.correction = static_cast<int>(v);
      out.aux.push_back({'D', index, v});
      return true;
    case 'H':
    case 'Q':
      out.aux.push_back({letter, index, v});
      return true;
    default:
      return false;
  }
}

bool Interpreter::Words(const Block& block, PreparedBlock& out) {
  const Program& p = program();
  eval_failed_ = false;
  // F and I/J/K are read once the block's G codes are known: in G33/G63/G64 F (MTC200) or K
  // (ISG) is the lead, wherever it stands in the block.
  std::optional<double> f_word;
  uint32_t f_offset = 0;
  uint32_t ijk_offset[3] = {0, 0, 0};
  uint8_t ijk = 0;
  // Two passes: the G codes and other words of a block act before its coordinates, wherever
  // they stand (X40 G16 is a diameter, X10 G91 an increment).
  // X1 / Y1 of a coordinate transformation (G31/G32): read with the axes, after the G codes.
  double fictive[2] = {std::nan(""), std::nan("")};
  uint32_t fictive_offset = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (const Word& w : p.Words(block)) {
      // A channel axis may be named like an address letter (C, X1): axes are looked up first.
      const int axis = AxisOf(w.address);
      if ((axis >= 0) != (pass == 1)) {
        if (pass == 0) continue;
        const std::string& name = p.symbols.Name(w.address);
        if (name != "X1" && name != "Y1") continue;
        const double v = w.value == kNoExpr ? w.number : Eval(w.value);
        if (eval_failed_) return Fail(eval_fail_offset_, eval_fail_message_);
        if (modal_.transformation == Transformation::kOff)
          return Fail(w.offset, "axis " + name +
                                    " is a fictive axis of a coordinate transformation: it needs "
                                    "G31 or G32 active");
        if (std::isnan(fictive[0]) && std::isnan(fictive[1])) fictive_offset = w.offset;
        fictive[name[0] - 'X'] = v;
        continue;
      }
      const std::string& address = p.symbols.Name(w.address);
      const double v = w.value == kNoExpr ? w.number : Eval(w.value);
      if (eval_failed_) return Fail(eval_fail_offset_, eval_fail_message_);
      const char letter = address[0];
      const int index = address.size() > 1 && std::isdigit(static_cast<unsigned char>(address[1]))
                            ? std::atoi(address.c_str() + 1)
                            : 0;
      if (axis >= 0) {
        double value = v;
        if (address == "X" && modal_.diameter) value = v / 2;  // G16: X is programmed as diameter
        out.target[axis] = modal_.incremental ? out.target[axis] + value : value;
        out.programmed |= uint64_t{1} << axis;
        continue;
      }
      if (address == "G") {
        if (!GWord(v, w.offset, out)) return false;
        continue;
      }
      if (AuxWord(letter, index, v, out)) continue;
      switch (letter) {
        case 'F':
          if (out.dwell_s < 0)
            out.dwell_s = v;
          else
            f_word = v, f_offset = w.offset, out.feed_programmed = true;
          continue;
        case 'I':
        case 'J':
        case 'K':
          out.centre[letter - 'I'] = v;
          out.has_centre = true;
          ijk |= 1 << (letter - 'I');
          ijk_offset[letter - 'I'] = w.offset;
          continue;
        case 'R':
          if (address == "R") {
            out.radius = v;
            continue;
          }
          break;  // RX RY RZ below
        default:
          break;
      }
      if (address == "X1" || address == "Y1") continue;  // read in pass 1
      if (address == "RX" || address == "RY" || address == "RZ") {
        const int k = address[1] - 'X';
        out.effective_distance[k] = v;
        out.has_effective_distance |= 1 << k;
        continue;
      }
      return Fail(w.offset, "axis " + address + " is not in this channel");
    }
  if (out.dwell_s < 0) return Fail(block.pos.offset, "G04 needs its dwell time as F");
  if ((!std::isnan(fictive[0]) || !std::isnan(fictive[1])) &&
      !FictiveWords(fictive, fictive_offset, ijk, ijk_offset, out))
    return false;
  if (!SpindleSynchronous(modal_.motion)) {
    if (f_word) modal_.feed = *f_word;
  } else if (!Lead(p.dialect, f_word, f_offset, ijk, ijk_offset, block.pos.offset, out)) {
    return false;
  }
  if (out.programmed && !out.homing && !out.set_position && !out.repos) out.motion = modal_.motion;
  return true;
}

int Interpreter::NamedAxis(const char* name) const {
  for (size_t a = 0; a < config_.axes.size(); ++a)
    if (config_.axes[a] == name) return static_cast<int>(a);
  return -1;
}

bool Interpreter::FictiveWords(const double fictive[2], uint32_t offset, uint8_t ijk,
                               const uint32_t ijk_offset[3], PreparedBlock& out) {
  const int xa = NamedAxis("X"), ca = NamedAxis("C");
  if (xa < 0 || ca < 0)
    return Fail(offset, "X1/Y1 need the axes X and C in this channel");
  const size_t x = static_cast<size_t>(xa), c = static_cast<size_t>(ca);
  out.programmed |= uint64_t{1} << x | uint64_t{1} << c;
  out.fictive = true;
  // G77 X1=0 Y1=0: the values do not count, X and C return to their targets along a straight
  // line of the fictive plane (REPOS manual 5.2, 8.3).
  if (out.repos) return true;
  // X1 is programmed as X is (G16: a diameter); Y1 is always a length.
  const double x1_scale = modal_.diameter ? 0.5 : 1.0;
  const auto word = [&](int k, double from) {
    const double v = k == 0 ? fictive[0] * x1_scale : fictive[1];
    if (std::isnan(v)) return from;
    return modal_.incremental ? from + v : v;
  };
  // The block starts where the program has X and C (a word of X or C in the same block is
  // overruled: the fictive axes carry the move).
  if (modal_.transformation == Transformation::kFace) {
    const FictivePoint start = MachineToFace(position_[x], position_[c]);
    const FictivePoint end{word(0, start.x1), word(1, start.y1)};
    double radius = 0, angle = 0;
    FaceToMachine(end, radius, angle);
    out.target[x] = radius;
    if (modal_.motion == Motion::kArcCw || modal_.motion == Motion::kArcCcw) {
      // G02/G03 in the face: centre I (X1) and J (Y1) relative to the start, as G17's I/J, or
      // R; C goes the way the arc goes round the centre (a full circle about it: 360 deg).
      if (ijk & 4)
        return Fail(ijk_offset[2], "K in an arc of G31: the centre in the face is I (X1), J (Y1)");
      std::string error;
      // An unprogrammed I or J is 0 (`centre` keeps the last block's values); the channel
      // plans the arc from the same words.
      if (!(ijk & 1)) out.centre[0] = 0;
      if (!(ijk & 2)) out.centre[1] = 0;
      const FaceArc arc = FaceArcOf(start, end, modal_.motion == Motion::kArcCw, out.has_centre,
                                    out.centre[0], out.centre[1], out.radius, error);
      if (!error.empty()) return Fail(offset, "G31 G02/G03: " + error);
      out.target[c] = position_[c] + FaceArcSweepDeg(arc);
      return true;
    }
    const bool start_at_centre = std::hypot(start.x1, start.y1) < 1e-12;
    out.target[c] = start_at_centre ? FaceC(end, position_[c])
                                    : position_[c] + SweepDeg(start, end);
    return true;
  }
  // G32: X1 is X; Y1 the arc length on the cylinder of modal_.cylinder_radius. An arc there
  // would lie in the unrolled surface (Z and Y1), a plane no G17/G18/G19 names: not offered,
  // rather than run as an arc of the active plane with C dragged along.
  if (modal_.motion == Motion::kArcCw || modal_.motion == Motion::kArcCcw)
    return Fail(offset, "G32 G02/G03: arcs in the cylinder surface are not offered; program "
                        "the curve as G01 lines in X1/Y1");
  const double r = modal_.cylinder_radius;
  out.target[x] = word(0, position_[x]);
  out.target[c] = CylinderC(word(1, CylinderY1(position_[c], r)), r);
  // The path feed counts C at the cylinder's radius (C-axis manual 1.2's effective distance).
  if (!(out.has_effective_distance & 3)) {
    out.effective_distance[0] = r;
    out.has_effective_distance |= 1;
  }
  return true;
}

}  // namespace vmt::control::nc
