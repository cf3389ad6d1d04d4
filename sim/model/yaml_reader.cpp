#include "sim/model/yaml_reader.hpp"

#include <yaml-cpp/eventhandler.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/input_file.hpp"
#include "sim/model/model_error.hpp"
#include "sim/model/nesting_depth.hpp"
#include "sim/model/yaml_text_checks.hpp"

namespace vmt::sim {

namespace {

// Most YAML nodes a file may have. The shipped scenes and models have a few thousand; yaml-cpp's
// tree costs about 500 bytes a node, so a 10 MB flow list would take gigabytes.
constexpr size_t kMaxYamlNodes = 200000;

// Counts the nodes of a document without building its tree, to refuse a huge one first.
class NodeCounter : public YAML::EventHandler {
 public:
  struct TooMany {};
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override { Count(); }
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override { Count(); }
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {
    Count();
  }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    Count();
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    Count();
  }
  void OnMapEnd() override {}

 private:
  void Count() {
    if (++nodes_ > kMaxYamlNodes) throw TooMany{};
  }
  size_t nodes_ = 0;
};

// Refuses a text that would overflow yaml-cpp's recursion or memory before it builds a tree.
void CheckYamlSize(const std::string& file, const std::string& text) {
  if (const int line = YamlNestingBeyond(text, kMaxNestingDepth))
    throw ModelError(file + ":" + std::to_string(line), "",
                     "nesting deeper than " + std::to_string(kMaxNestingDepth) + " levels");
  std::istringstream in(text);
  YAML::Parser parser(in);
  NodeCounter counter;
  try {
    while (parser.HandleNextDocument(counter)) {
    }
  } catch (const NodeCounter::TooMany&) {
    throw ModelError(file, "",
                     "more than " + std::to_string(kMaxYamlNodes) + " YAML nodes (the limit)");
  }
}

}  // namespace

YamlNode YamlNode::LoadFile(const std::string& file) {
  std::string text, why;
  if (!common::ReadInputFile(file, text, why))
    throw ModelError(file, "", "cannot open file: " + why);
  try {
    CheckYamlSize(file, text);
    CheckUtf8Text(file, text);
    const YAML::Node root = YAML::Load(text);
    CheckMapKeys(file, root);
    return YamlNode(root, file, "");
  } catch (const YAML::Exception& e) {
    throw ModelError(YamlSyntaxError(file, e));
  }
}

void YamlNode::Fail(const std::string& message) const {
  std::string where = file_;
  const YAML::Mark mark = node_.IsDefined() ? node_.Mark() : YAML::Mark::null_mark();
  if (mark.line >= 0)
    where += ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
  throw ModelError(where, path_.empty() ? "(top level)" : path_, message);
}

bool YamlNode::Has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

YamlNode YamlNode::operator[](const std::string& key) const {
  if (!node_.IsMap()) Fail("expected a map with key '" + key + "'");
  const YAML::Node child = node_[key];
  const std::string child_path = path_.empty() ? key : path_ + "." + key;
  if (!child.IsDefined() || child.IsNull()) Fail("missing required key '" + key + "'");
  return YamlNode(child, file_, child_path);
}

YamlNode YamlNode::operator[](size_t index) const {
  if (!node_.IsSequence()) Fail("expected a list");
  if (index >= node_.size()) Fail("index " + std::to_string(index) + " out of range");
  return YamlNode(node_[index], file_, path_ + "[" + std::to_string(index) + "]");
}

size_t YamlNode::size() const {
  if (!node_.IsSequence()) Fail("expected a list");
  return node_.size();
}

std::vector<std::string> YamlNode::Keys() const {
  if (!node_.IsMap()) Fail("expected a map");
  std::vector<std::string> keys;
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar()) YamlNode(kv.first, file_, path_).Fail("a key must be a name");
    keys.push_back(kv.first.Scalar());
  }
  return keys;
}

YamlNode YamlNode::KeyNode(const std::string& key) const {
  const std::string key_path = path_.empty() ? key : path_ + "." + key;
  if (node_.IsMap())
    for (const auto& kv : node_)
      if (kv.first.IsScalar() && kv.first.Scalar() == key)
        return YamlNode(kv.first, file_, key_path);
  return YamlNode(node_, file_, key_path);
}

void YamlNode::AllowKeys(std::initializer_list<const char*> allowed) const {
  for (const std::string& key : Keys()) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || key == a;
    if (ok) continue;
    std::string list;
    for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
    KeyNode(key).Fail("unknown key '" + key + "' (expected one of: " + list + ")");
  }
}

namespace {

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

}  // namespace

double YamlNode::Double(double min, double max) const {
  if (!node_.IsScalar()) Fail("expected a number");
  double v = 0;
  try {
    v = node_.as<double>();
  } catch (const YAML::Exception&) {
    Fail("expected a number, got \"" + node_.Scalar() + "\"");
  }
  if (!std::isfinite(v)) Fail("expected a finite number, got \"" + node_.Scalar() + "\"");
  if (v < min || v > max)
    Fail("must be in " + Number(min) + ".." + Number(max) + ", got " + node_.Scalar());
  return v;
}

int YamlNode::Int(int min, int max) const {
  if (!node_.IsScalar()) Fail("expected a whole number");
  int v = 0;
  try {
    v = node_.as<int>();
  } catch (const YAML::Exception&) {
    Fail("expected a whole number in " + std::to_string(min) + ".." + std::to_string(max) +
         ", got \"" + node_.Scalar() + "\"");
  }
  if (v < min || v > max)
    Fail("must be in " + std::to_string(min) + ".." + std::to_string(max) + ", got " +
         node_.Scalar());
  return v;
}

int YamlNode::Int() const {
  constexpr int kAnyInt = static_cast<int>(kAnyNumber);
  return Int(-kAnyInt, kAnyInt);
}

bool YamlNode::Bool() const {
  if (!node_.IsScalar()) Fail("expected true or false");
  try {
    return node_.as<bool>();
  } catch (const YAML::Exception&) {
    Fail("expected true or false, got \"" + node_.Scalar() + "\"");
  }
}

std::string YamlNode::String() const {
  if (!node_.IsScalar()) Fail("expected a string");
  return node_.Scalar();
}

double YamlNode::Double(const std::string& key, double fallback, double min, double max) const {
  return Has(key) ? (*this)[key].Double(min, max) : fallback;
}
int YamlNode::Int(const std::string& key, int fallback, int min, int max) const {
  return Has(key) ? (*this)[key].Int(min, max) : fallback;
}
int YamlNode::Int(const std::string& key, int fallback) const {
  return Has(key) ? (*this)[key].Int() : fallback;
}
bool YamlNode::Bool(const std::string& key, bool fallback) const {
  return Has(key) ? (*this)[key].Bool() : fallback;
}
std::string YamlNode::String(const std::string& key, const std::string& fallback) const {
  return Has(key) ? (*this)[key].String() : fallback;
}

std::vector<double> YamlNode::Doubles(size_t n, double min, double max) const {
  if (!node_.IsSequence() || node_.size() != n)
    Fail("expected a list of " + std::to_string(n) + " numbers");
  std::vector<double> out;
  for (size_t i = 0; i < n; ++i) out.push_back((*this)[i].Double(min, max));
  return out;
}

}  // namespace vmt::sim
