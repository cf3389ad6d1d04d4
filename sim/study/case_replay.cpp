#include "sim/study/case_replay.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/json_text.hpp"
#include "common/output_file.hpp"
#include "sim/study/case_files.hpp"
#include "sim/study/reference_run.hpp"
#include "sim/study/scratch_folder.hpp"
#include "sim/study/study_cases.hpp"
#include "sim/study/study_source.hpp"

namespace vmt::sim::study {
namespace {

nlohmann::json ReadJson(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": missing (" + what + ")");
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw std::runtime_error(path + ": not a JSON object");
  return j;
}

}  // namespace

std::string CaseFolderOf(const std::string& case_id) { return "cases/" + FileNameOf(case_id); }

std::string SaveCase(const std::string& dir, const std::string& case_id) {
  const std::string folder = dir + "/" + CaseFolderOf(case_id);
  if (std::filesystem::exists(folder + "/case.json")) {
    const nlohmann::json saved = ReadJson(folder + "/case.json", "a saved case");
    if (saved.value("case", "") != case_id)
      throw std::runtime_error(folder + " holds case " + saved.value("case", "?") + ", not " +
                               case_id);
    return folder;
  }
  const StudyCases study = LoadStudyCases(dir);
  const CaseSpace space = study.space();
  const std::optional<size_t> k = space.IndexOf(case_id);
  if (!k)
    throw UnknownCase("the study in " + dir + " has no case " + case_id +
                      " (cases.csv lists them)");

  // Saved under another name first and renamed, so that a folder is either whole or absent.
  const ScratchFolder scratch(folder + ".saving-" + std::to_string(::getpid()));
  const std::string& work = scratch.path();
  const SavedCase saved =
      SaveCaseRun(study.scene, study.plan, study.interruptions, space.At(*k), work);
  nlohmann::ordered_json j;
  j["case"] = case_id;
  j["scene_file"] = study.source.scene_file;
  j["subroutine_file"] = saved.subroutine_file;
  j["until_s"] = saved.until_s;
  j["trace_digest"] = saved.trace_digest;
  j["timeline"] = saved.timeline;
  j["result"] = saved.result;
  common::WriteFileAtomically(work + "/case.json",
                              j.dump(1, ' ', false, common::kReplaceBadUtf8) + "\n");
  std::error_code ec;
  std::filesystem::rename(work, folder, ec);  // failing, another request saved it meanwhile
  return folder;
}

std::optional<CaseReplay> ReadCaseReplay(const std::string& run_dir) {
  const std::string path = run_dir + "/case.json";
  if (!std::filesystem::exists(path)) return std::nullopt;
  const nlohmann::json j = ReadJson(path, "a saved case");
  try {
    SavedCase saved;
    saved.timeline = j.at("timeline").get<std::vector<std::string>>();
    saved.subroutine_file = j.at("subroutine_file").get<std::string>();
    CaseReplay replay;
    replay.until_s = j.at("until_s").get<double>();
    replay.trace_digest = j.at("trace_digest").get<std::string>();
    replay.scene = SavedCaseScene(LoadScene(j.at("scene_file").get<std::string>()), saved);
    return replay;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace vmt::sim::study
