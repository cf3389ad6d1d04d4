#pragma once
// Reading user YAML (machine and scene files) so that every fault names the file, the line and
// the YAML path, e.g. `scene.yaml:12:7: timeline[3].move.to: expected a number, got "fast"`.

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <string>
#include <vector>

namespace vmt::sim {

class YamlNode {
 public:
  /// Parses a file; throws ModelError on I/O or syntax errors.
  static YamlNode LoadFile(const std::string& file);

  YamlNode(YAML::Node node, std::string file, std::string path)
      : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}

  bool Has(const std::string& key) const;
  /// Required key.
  YamlNode operator[](const std::string& key) const;
  /// Sequence element.
  YamlNode operator[](size_t index) const;
  size_t size() const;
  bool IsMap() const { return node_.IsMap(); }
  bool IsSequence() const { return node_.IsSequence(); }
  bool IsScalar() const { return node_.IsScalar(); }
  /// Keys of a map, in file order.
  std::vector<std::string> Keys() const;
  /// Every key must be one of `allowed`: catches typos that would silently do nothing.
  void AllowKeys(std::initializer_list<const char*> allowed) const;

  /// The key itself (its place in the file), for a fault in the key rather than its value.
  YamlNode KeyNode(const std::string& key) const;

  /// A number in [min, max]: every number is read with the range its key allows, and a value
  /// outside it names the range (`must be in 0..1000, got 1e+308`).
  double Double(double min, double max) const;
  double Double(const std::string& key, double fallback, double min, double max) const;
  /// A whole number in [min, max].
  int Int(int min, int max) const;
  int Int(const std::string& key, int fallback, int min, int max) const;
  /// A sequence of exactly n numbers, each in [min, max].
  std::vector<double> Doubles(size_t n, double min, double max) const;
  /// Without a range of its own, a number is at most kAnyNumber in magnitude: larger ones are
  /// no length, speed or time of a machine tool, and would overflow what is computed of them.
  static constexpr double kAnyNumber = 1e9;
  double Double() const { return Double(-kAnyNumber, kAnyNumber); }
  double Double(const std::string& key, double fallback) const {
    return Double(key, fallback, -kAnyNumber, kAnyNumber);
  }
  int Int() const;
  int Int(const std::string& key, int fallback) const;
  std::vector<double> Doubles(size_t n) const { return Doubles(n, -kAnyNumber, kAnyNumber); }
  bool Bool() const;
  std::string String() const;
  bool Bool(const std::string& key, bool fallback) const;
  std::string String(const std::string& key, const std::string& fallback) const;

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  [[noreturn]] void Fail(const std::string& message) const;

 private:
  YAML::Node node_;
  std::string file_;
  std::string path_;
};

}  // namespace vmt::sim
