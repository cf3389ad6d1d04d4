#include "control/nc/parser.hpp"

#include <algorithm>
#include <optional>

#include "common/huge_pages.hpp"
#include "common/mapped_file.hpp"
#include "control/nc/front_end.hpp"
#include "control/nc/program_check.hpp"

namespace vmt::control::nc {

const char* ToString(Dialect d) { return d == Dialect::kIsg ? "isg" : "mtc200"; }

std::string Format(const Diagnostic& d, const std::vector<std::string>& files) {
  const std::string& file = d.pos.file < files.size() ? files[d.pos.file] : "<input>";
  return file + ":" + std::to_string(d.pos.line) + ":" + std::to_string(d.pos.column) +
         ": error: " + d.message;
}

uint32_t Symbols::Intern(std::string_view name) {
  Cached* cached = nullptr;
  uint64_t key = 0;
  if (!name.empty() && name.size() < 8) {
    // Byte by byte: a memcpy into the key stalls its load (store forwarding) on every lookup.
    for (size_t i = 0; i < name.size(); ++i)
      key |= uint64_t{static_cast<unsigned char>(name[i])} << (8 * i);
    key |= uint64_t{name.size()} << 56;
    cached = &cache_[(key * 0x9E3779B97F4A7C15ull) >> 56];
    if (cached->key == key) return cached->id;
  }
  uint32_t id;
  if (auto it = ids_.find(name); it != ids_.end()) {
    id = it->second;
  } else {
    id = static_cast<uint32_t>(names_.size());
    ids_.emplace(names_.emplace_back(name), id);
  }
  if (cached) *cached = {key, id};
  return id;
}

uint32_t Symbols::Find(std::string_view name) const {
  auto it = ids_.find(name);
  return it == ids_.end() ? 0 : it->second;
}

SourcePos Program::PosAt(uint32_t offset) const {
  const auto it = std::upper_bound(line_starts.begin(), line_starts.end(), offset);
  const auto line = static_cast<uint32_t>(it - line_starts.begin());
  if (line == 0) return {0, 1, offset + 1, offset};
  return {0, line, offset - line_starts[line - 1] + 1, offset};
}

// Editors on Windows start a UTF-8 file with a byte order mark: it is no part of the program.
static size_t Utf8BomLength(std::string_view text) {
  return text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
}

Dialect DetectDialect(std::string_view text, std::string_view file_name) {
  auto ends_with = [&](std::string_view ext) {
    return file_name.size() >= ext.size() && file_name.substr(file_name.size() - ext.size()) == ext;
  };
  if (ends_with(".isg") || ends_with(".ISG")) return Dialect::kIsg;
  if (ends_with(".mtc") || ends_with(".MTC")) return Dialect::kMtc200;
  for (size_t i = Utf8BomLength(text); i < text.size();) {
    size_t end = text.find('\n', i);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(i, end - i);
    i = end + 1;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || line[first] == ';' || line[first] == '(') continue;
    line = line.substr(first);
    if (line[0] == '%' || line.find('$') != std::string_view::npos ||
        line.find('#') != std::string_view::npos || line.find('[') != std::string_view::npos)
      return Dialect::kIsg;
    if (line.find('@') != std::string_view::npos || line.find(" .") != std::string_view::npos ||
        line[0] == '.')
      return Dialect::kMtc200;
    if ((line[0] == 'N' || line[0] == 'n') && line.size() > 5 &&
        line.substr(1, 4).find_first_not_of("0123456789") == std::string_view::npos)
      return Dialect::kMtc200;
  }
  return Dialect::kMtc200;
}

ParseResult ParseProgram(std::string_view text, const std::string& file_name, Dialect dialect) {
  ParseResult r;
  Program& p = r.program;
  p.dialect = dialect;
  p.files.push_back(file_name);
  // Reserve the arenas once, for what the text can hold, so that a million-block program does
  // not spend its time copying them as they grow; huge pages make their first touch cheap.
  const size_t lines = static_cast<size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  common::ReserveHugePages(p.line_starts, lines);
  common::ReserveHugePages(p.blocks, lines);
  common::ReserveHugePages(p.statements, lines + lines / 4);
  common::ReserveHugePages(p.words, text.size() / 6 + 16);
  common::ReserveHugePages(p.code, text.size() / 3 + 16);
  ExpressionParser expr(p, r.errors);
  const auto parse_line = dialect == Dialect::kIsg ? ParseIsgLine : ParseMtc200Line;
  uint32_t line_number = 0, counter = 0;
  // Offsets stay those of the whole text; the first line starts after the mark.
  for (size_t i = Utf8BomLength(text); i <= text.size();) {
    size_t end = text.find('\n', i);
    if (end == std::string_view::npos) end = text.size();
    ++line_number;
    p.line_starts.push_back(static_cast<uint32_t>(i));
    SourcePos start{0, line_number, 1, static_cast<uint32_t>(i)};
    Block block;
    block.first_word = static_cast<uint32_t>(p.words.size());
    block.first_statement = static_cast<uint32_t>(p.statements.size());
    const size_t errors_before = r.errors.size();
    if (parse_line(text.substr(i, end - i), start, expr, block)) {
      block.counter = ++counter;
      block.num_words = static_cast<uint32_t>(p.words.size()) - block.first_word;
      block.num_statements = static_cast<uint32_t>(p.statements.size()) - block.first_statement;
      p.blocks.push_back(block);
    }
    // One error per block: what follows a fault on the same line is not worth reporting.
    if (r.errors.size() > errors_before + 1) r.errors.resize(errors_before + 1);
    if (end == text.size()) break;
    i = end + 1;
  }
  if (p.name.empty()) {
    const size_t slash = file_name.find_last_of('/');
    std::string stem = file_name.substr(slash == std::string::npos ? 0 : slash + 1);
    p.name = stem.substr(0, stem.find('.'));
  }
  CheckProgram(p, r.errors);
  std::stable_sort(r.errors.begin(), r.errors.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return a.pos.offset < b.pos.offset;
  });
  return r;
}

ParseResult ParseFile(const std::string& path, Dialect dialect) {
  std::string why;
  const std::optional<common::MappedFile> text = common::MappedFile::Read(path, &why);
  if (!text) {
    ParseResult r;
    r.program.files.push_back(path);
    r.errors.push_back({{0, 0, 0, 0}, "cannot open file: " + why});
    return r;
  }
  return ParseProgram(*text, path, dialect);
}

}  // namespace vmt::control::nc
