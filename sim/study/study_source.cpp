#include "sim/study/study_source.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/json_text.hpp"
#include "common/output_file.hpp"
#include "sim/study/case_merge.hpp"
#include "sim/study/reference_run.hpp"

namespace vmt::sim::study {
namespace {

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

}  // namespace

StudySource SourceOf(const std::string& scene_file, const StudyPlan& plan) {
  StudySource s;
  s.scene_file = std::filesystem::absolute(scene_file).lexically_normal().string();
  s.every_ms = plan.every_ms;
  s.per_mille = plan.per_mille;
  return s;
}

void WriteStudySource(const std::string& dir, const StudySource& source) {
  nlohmann::ordered_json j;
  j["scene_file"] = source.scene_file;
  j["every_ms"] = source.every_ms;
  j["per_mille"] = source.per_mille;
  // A whole study's record stays as it always was; only a share says which.
  if (source.shards > 1) {
    j["shard"] = source.shard;
    j["shards"] = source.shards;
  }
  if (source.max_cases) j["max_cases"] = *source.max_cases;
  common::WriteFileAtomically(dir + "/study.json",
                              j.dump(1, ' ', false, common::kReplaceBadUtf8) + "\n");
}

std::optional<StudySource> ReadStudySource(const std::string& dir) {
  const std::string path = dir + "/study.json";
  if (!std::filesystem::exists(path)) return std::nullopt;
  const nlohmann::json j = nlohmann::json::parse(ReadText(path), nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw std::runtime_error(path + ": not a JSON object");
  const auto bad = [&](const std::string& key, const std::string& what) {
    return std::runtime_error(path + ": " + key + ": expected " + what);
  };
  StudySource s;
  if (!j.contains("scene_file") || !j["scene_file"].is_string())
    throw bad("scene_file", "the scene's path");
  s.scene_file = j["scene_file"].get<std::string>();
  if (j.contains("every_ms")) {
    if (!j["every_ms"].is_number()) throw bad("every_ms", "a number");
    s.every_ms = j["every_ms"].get<double>();
  }
  if (j.contains("per_mille")) {
    if (!j["per_mille"].is_array()) throw bad("per_mille", "a list of numbers 0..1000");
    for (const nlohmann::json& p : j["per_mille"]) {
      if (!p.is_number_integer() || p.get<int64_t>() < 0 || p.get<int64_t>() > 1000)
        throw bad("per_mille", "a list of numbers 0..1000");
      s.per_mille.push_back(p.get<int>());
    }
  }
  const auto whole = [&](const char* key, int64_t most) -> std::optional<int64_t> {
    if (!j.contains(key)) return std::nullopt;
    if (!j[key].is_number_integer() || j[key].get<int64_t>() < 1 || j[key].get<int64_t>() > most)
      throw bad(key, "a whole number 1.." + std::to_string(most));
    return j[key].get<int64_t>();
  };
  s.shards = static_cast<int>(whole("shards", 1000000).value_or(1));
  s.shard = static_cast<int>(whole("shard", s.shards).value_or(1));
  if (const std::optional<int64_t> n = whole("max_cases", 1000000000))
    s.max_cases = static_cast<size_t>(*n);
  return s;
}

std::vector<bool> ShareOf(const CaseSpace& space, const StudySource& source) {
  std::vector<bool> mine(space.size(), false);
  size_t n = 0;
  for (size_t k = 0; k < space.size() && (!source.max_cases || n < *source.max_cases); ++k) {
    if (InShard(k / space.cases_per_group(), source.shard, source.shards)) {
      mine[k] = true;
      ++n;
    }
  }
  return mine;
}

std::vector<bool> HeldCases(const CaseSpace& space, const std::string& jsonl_path) {
  std::vector<bool> held(space.size(), false);
  if (!std::filesystem::exists(jsonl_path)) return held;
  ForEachCase(jsonl_path, [&](const CaseResult& r) {
    if (const std::optional<size_t> k = space.IndexOf(r["case"].get<std::string>()))
      held[*k] = true;
  });
  return held;
}

StudyCases LoadStudyCases(const std::string& dir) {
  std::optional<StudySource> source = ReadStudySource(dir);
  if (!source)
    throw std::runtime_error(dir +
                             ": no study.json (not a study folder, or one made before studies "
                             "recorded their scene: run the study again)");
  if (!std::filesystem::exists(dir + "/reference.json"))
    throw std::runtime_error(dir + ": no reference.json (the study's reference run has not ended)");
  Scene scene = LoadScene(source->scene_file);
  StudyPlan plan = LoadStudyPlan(source->scene_file, scene);
  plan.every_ms = source->every_ms;
  plan.per_mille = source->per_mille;
  Reference ref;
  try {
    ref = ReferenceFromJson(ReadText(dir + "/reference.json"));
  } catch (const std::exception& e) {
    throw std::runtime_error(dir + "/reference.json: " + e.what());
  }
  std::vector<Interruption> interruptions = Interruptions(plan, ref);
  return {std::move(*source), std::move(scene), std::move(plan), std::move(interruptions)};
}

}  // namespace vmt::sim::study
