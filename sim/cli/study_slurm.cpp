#include "sim/cli/study_slurm.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "sim/cli/option_checks.hpp"
#include "sim/study/slurm_job.hpp"
#include "sim/study/study_plan.hpp"
#include "sim/study/study_status.hpp"

namespace vmt::sim {
namespace {

using study::SlurmStudy;

// "250,750": points 0..1000 of a block, as `vmt study repos --per-mille` takes them.
const CLI::Validator kPerMilleList(
    [](std::string& text) -> std::string {
      std::stringstream ss(text);
      size_t points = 0;
      for (std::string p; std::getline(ss, p, ',');) {
        char* end = nullptr;
        const long v = std::strtol(p.c_str(), &end, 10);
        if (p.empty() || *end != '\0' || v < 0 || v > 1000)
          return "expected numbers 0..1000, e.g. 250,750, got '" + text + "'";
        ++points;
      }
      return points ? "" : "expected numbers 0..1000, e.g. 250,750, got ''";
    },
    "LIST");

// A #SBATCH line takes its words as they stand: no blanks, quotes or Slurm's % patterns.
std::string SlurmPathError(const std::string& path) {
  if (path.find_first_of(" \t\n'\"%$`\\") != std::string::npos)
    return path + ": a Slurm study's folder may not hold blanks, quotes, %, $, ` or \\";
  return "";
}

std::string SbatchCommandOf(const SlurmStudy& s) {
  std::string c = "vmt study sbatch " + study::ShellQuoted(s.scene) + " --out " +
                  study::ShellQuoted(s.dir) + " --shards " + std::to_string(s.shards);
  for (const std::string& o : s.repos_options) c += " " + study::ShellQuoted(o);
  return c;
}

int Sbatch(SlurmStudy wanted, bool print) {
  const Scene scene = LoadScene(wanted.scene);
  study::LoadStudyPlan(wanted.scene,
                       scene);  // a scene without a study: plan fails here, not on the nodes
  wanted.scene = std::filesystem::absolute(wanted.scene).lexically_normal().string();
  wanted.dir = std::filesystem::absolute(wanted.dir).lexically_normal().string();
  while (wanted.dir.size() > 1 && wanted.dir.back() == '/') wanted.dir.pop_back();
  wanted.vmt = std::filesystem::read_symlink("/proc/self/exe").string();
  for (const std::string& path : {wanted.scene, wanted.dir, wanted.vmt})
    if (const std::string error = SlurmPathError(path); !error.empty()) {
      std::fprintf(stderr, "vmt study sbatch: error: %s\n", error.c_str());
      return 2;
    }
  if (const std::optional<SlurmStudy> held = study::ReadSlurmStudy(wanted.dir)) {
    if (held->scene != wanted.scene || held->shards != wanted.shards ||
        held->repos_options != wanted.repos_options) {
      std::fprintf(stderr,
                   "vmt study sbatch: error: %s holds another Slurm study (%s); submit that "
                   "command again to complete it, or choose another --out\n",
                   wanted.dir.c_str(), SbatchCommandOf(*held).c_str());
      return 2;
    }
  }
  study::WriteSlurmScripts(wanted);
  std::printf("%s/slurm/{shards.sh,merge.sh,job.json}: %d shard(s) of %s\n", wanted.dir.c_str(),
              wanted.shards, wanted.scene.c_str());
  const study::StudyProgress merged = study::ReadStudyProgress(wanted.dir);
  if (merged.complete() && study::IncompleteShards(wanted).empty()) {
    std::printf("%s: complete (%zu cases), nothing to submit\n", wanted.dir.c_str(), merged.done);
    return 0;
  }
  const study::SlurmSubmission s = study::SubmitSlurmStudy(wanted, !print);
  std::string shards;
  for (const int k : s.shards) shards += (shards.empty() ? "" : ",") + std::to_string(k);
  if (print) {
    std::printf("to submit (the shards %s, then the merge):\n",
                shards.empty() ? "are complete" : shards.c_str());
    for (const std::vector<std::string>& command : s.commands) {
      std::string line;
      for (const std::string& word : command) line += (line.empty() ? "" : " ") + word;
      std::printf("  %s\n", line.c_str());
    }
    return 0;
  }
  if (!s.array_job.empty())
    std::printf("submitted: array job %s (shards %s), merge job %s after it\n", s.array_job.c_str(),
                shards.c_str(), s.merge_job.c_str());
  else
    std::printf("submitted: merge job %s (every shard is complete)\n", s.merge_job.c_str());
  std::printf("follow it: squeue; vmt study status %s\n", wanted.dir.c_str());
  return 0;
}

// Prints a folder's line and, with `list`, its missing cases; true when it is complete.
bool Report(const study::StudyProgress& p, const std::string& name, bool list) {
  study::StudyProgress shown = p;
  shown.dir = name;
  std::printf("%s\n", study::ProgressLine(shown).c_str());
  if (list)
    for (const std::string& id : p.missing) std::printf("  missing: %s\n", id.c_str());
  return p.complete();
}

int Status(const std::vector<std::string>& dirs, bool list) {
  bool complete = true;
  for (const std::string& dir : dirs) {
    if (!std::filesystem::is_directory(dir)) {
      std::fprintf(stderr, "vmt study status: error: %s: not a folder\n", dir.c_str());
      return 2;
    }
    const std::optional<SlurmStudy> slurm = study::ReadSlurmStudy(dir);
    if (!slurm) {
      complete = Report(study::ReadStudyProgress(dir), dir, list) && complete;
      continue;
    }
    std::vector<int> left;
    for (int k = 1; k <= slurm->shards; ++k)
      if (!Report(study::ReadStudyProgress(study::ShardFolder(*slurm, k)),
                  dir + "/shards/" + std::to_string(k), list))
        left.push_back(k);
    const study::StudyProgress merged = study::ReadStudyProgress(dir);
    if (merged.source)
      complete = Report(merged, dir + " (merged)", false) && complete;
    else
      std::printf("%s (merged): not yet\n", dir.c_str());
    complete = complete && merged.complete() && left.empty();
    if (!left.empty()) {
      std::string shards;
      for (const int k : left) shards += (shards.empty() ? "" : ",") + std::to_string(k);
      std::printf(
          "shards %s incomplete: `%s` submits them alone (each keeps its finished "
          "cases), and the merge\n",
          shards.c_str(), SbatchCommandOf(*slurm).c_str());
    } else if (!merged.complete()) {
      std::printf("every shard is complete, the merge is not: `%s` submits it\n",
                  SbatchCommandOf(*slurm).c_str());
    }
  }
  return complete ? 0 : 1;
}

}  // namespace

std::vector<std::pair<CLI::App*, std::function<int()>>> AddStudySlurmCommands(CLI::App& parent) {
  struct Args {
    SlurmStudy study;
    std::string every_ms, per_mille, max_cases, snapshots;
    bool print = false;
    std::vector<std::string> status_dirs;
    bool missing = false;
  };
  auto o = std::make_shared<Args>();
  CLI::App* sbatch = parent.add_subcommand(
      "sbatch",
      "Run a study on a Slurm cluster: the shards as one array job, the merge after them "
      "(again into the same folder: only what is not complete)");
  sbatch->add_option("scene", o->study.scene, "Scene file with a study: section")->required();
  sbatch->add_option("--out", o->study.dir, "Study folder on a folder every node sees")
      ->required()
      ->check(kOutputFolder);
  sbatch->add_option("--shards", o->study.shards, "Shards: array tasks")
      ->required()
      ->check(WholeIn(1, 100000));
  sbatch->add_option("--cpus-per-task", o->study.cpus_per_task, "Worker processes per shard")
      ->check(WholeIn(1, 256))
      ->capture_default_str();
  sbatch->add_option("--every-ms", o->every_ms, "Interrupt every T ms of the program's run")
      ->check(FiniteIn(1, 1e7, "number of ms"));
  sbatch->add_option("--per-mille", o->per_mille, "Interrupt every motion block at these points")
      ->check(kPerMilleList)
      ->excludes("--every-ms");
  sbatch->add_option("--max-cases", o->max_cases, "Only the first N cases of each shard")
      ->check(WholeIn(1, 1000000000));
  sbatch->add_option("--snapshots", o->snapshots, "Pictures of each shard's worst cases")
      ->check(WholeIn(0, 100));
  sbatch
      ->add_option("--sbatch-option", o->study.sbatch_options,
                   "One more #SBATCH option for both jobs, e.g. --partition=long (repeatable)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            if (text.rfind("--", 0) != 0 || text.find('\n') != std::string::npos)
              return "expected one --name[=value], got '" + text + "'";
            return "";
          },
          "--OPTION"));
  sbatch->add_flag("--print", o->print,
                   "Write the scripts and print the sbatch commands instead of submitting");
  CLI::App* status = parent.add_subcommand(
      "status",
      "Which cases a study folder, its shards or a Slurm study still lack (exit 0 complete, 1 "
      "not)");
  status->add_option("dirs", o->status_dirs, "Study folders")->required();
  status->add_flag("--missing", o->missing, "List every missing case id");
  return {{sbatch,
           [o] {
             SlurmStudy s = o->study;
             const std::pair<const char*, const std::string*> passed[] = {
                 {"--every-ms", &o->every_ms},
                 {"--per-mille", &o->per_mille},
                 {"--max-cases", &o->max_cases},
                 {"--snapshots", &o->snapshots}};
             for (const auto& [name, value] : passed)
               if (!value->empty()) s.repos_options.insert(s.repos_options.end(), {name, *value});
             return Sbatch(s, o->print);
           }},
          {status, [o] { return Status(o->status_dirs, o->missing); }}};
}

}  // namespace vmt::sim
