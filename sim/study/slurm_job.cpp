#include "sim/study/slurm_job.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "common/json_text.hpp"
#include "common/output_file.hpp"
#include "sim/study/study_status.hpp"

extern char** environ;

namespace vmt::sim::study {
namespace {

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

std::string ReadAll(int fd) {
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    text.append(buffer, static_cast<size_t>(n));
  }
  return text;
}

std::string Trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

// Runs `args` (looked up on PATH) and returns what it printed; throws with its own message
// when it cannot be started or fails.
std::string Run(const std::vector<std::string>& args) {
  int out[2], err[2];
  if (::pipe(out) != 0 || ::pipe(err) != 0) throw std::runtime_error("pipe failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err[1], 2);
  posix_spawn_file_actions_addclose(&actions, out[0]);
  posix_spawn_file_actions_addclose(&actions, err[0]);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = ::posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out[1]);
  ::close(err[1]);
  if (spawned != 0) {
    ::close(out[0]);
    ::close(err[0]);
    if (spawned == ENOENT)
      throw std::runtime_error(args[0] +
                               " not found: this is not a Slurm submit host (--print writes the "
                               "scripts and prints the commands to submit them elsewhere)");
    throw std::runtime_error(args[0] + ": " + std::strerror(spawned));
  }
  // sbatch prints a line or two: the error pipe cannot fill while the output is read.
  const std::string printed = ReadAll(out[0]);
  const std::string complaint = ReadAll(err[0]);
  ::close(out[0]);
  ::close(err[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(args[0] +
                             " refused: " + Trimmed(complaint.empty() ? printed : complaint));
  return printed;
}

// `sbatch --parsable` prints "ID" or "ID;CLUSTER".
std::string JobId(const std::string& printed) {
  const std::string id = Trimmed(printed.substr(0, printed.find(';')));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw std::runtime_error("sbatch printed no job id: " + Trimmed(printed));
  return id;
}

std::string Joined(const std::vector<int>& numbers) {
  std::string s;
  for (const int n : numbers) s += (s.empty() ? "" : ",") + std::to_string(n);
  return s;
}

std::string SlurmFolder(const SlurmStudy& study) { return study.dir + "/slurm"; }

}  // namespace

std::string ShellQuoted(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                              "0123456789_./=:,+-@%") == std::string::npos)
    return word;
  std::string q = "'";
  for (const char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string ShardFolder(const SlurmStudy& study, int k) {
  return study.dir + "/shards/" + std::to_string(k);
}

void WriteSlurmScripts(const SlurmStudy& s) {
  const std::string folder = SlurmFolder(s);
  std::filesystem::create_directories(folder);
  const std::string n = std::to_string(s.shards);
  std::string shards =
      "#!/bin/bash\n"
      "# Shard K of " +
      n +
      " of a vmt REPOS study, K = the array task: written by\n"
      "# `vmt study sbatch`, which submits it (again: only the shards not complete).\n"
      "#SBATCH --job-name=vmt-study\n"
      "#SBATCH --array=1-" +
      n +
      "\n"
      "#SBATCH --cpus-per-task=" +
      std::to_string(s.cpus_per_task) +
      "\n"
      "#SBATCH --requeue\n"
      "#SBATCH --open-mode=append\n"
      "#SBATCH --output=" +
      folder + "/shard-%a.log\n";
  for (const std::string& o : s.sbatch_options) shards += "#SBATCH " + o + "\n";
  shards += "set -eu\nk=$SLURM_ARRAY_TASK_ID\n";
  shards += "exec " + ShellQuoted(s.vmt) + " study repos " + ShellQuoted(s.scene) + " --out " +
            ShellQuoted(s.dir + "/shards") + "/\"$k\" --shard \"$k/" + n +
            "\" --jobs \"${SLURM_CPUS_PER_TASK:-" + std::to_string(s.cpus_per_task) + "}\"";
  for (const std::string& o : s.repos_options) shards += " " + ShellQuoted(o);
  shards += "\n";

  std::string merge =
      "#!/bin/bash\n"
      "# Joins the " +
      n +
      " shards of a vmt REPOS study once all hold every case: written by\n"
      "# `vmt study sbatch`, which submits it after the shards.\n"
      "#SBATCH --job-name=vmt-study-merge\n"
      "#SBATCH --open-mode=append\n"
      "#SBATCH --output=" +
      folder + "/merge.log\n";
  for (const std::string& o : s.sbatch_options) merge += "#SBATCH " + o + "\n";
  std::string dirs;
  for (int k = 1; k <= s.shards; ++k) dirs += " " + ShellQuoted(ShardFolder(s, k));
  merge += "set -eu\n";
  merge += ShellQuoted(s.vmt) + " study status" + dirs + "\n";
  merge +=
      "exec " + ShellQuoted(s.vmt) + " study merge" + dirs + " --out " + ShellQuoted(s.dir) + "\n";

  nlohmann::ordered_json j;
  j["vmt"] = s.vmt;
  j["scene"] = s.scene;
  j["dir"] = s.dir;
  j["shards"] = s.shards;
  j["cpus_per_task"] = s.cpus_per_task;
  j["repos_options"] = s.repos_options;
  j["sbatch_options"] = s.sbatch_options;
  common::WriteFileAtomically(folder + "/shards.sh", shards);
  common::WriteFileAtomically(folder + "/merge.sh", merge);
  common::WriteFileAtomically(folder + "/job.json",
                              j.dump(1, ' ', false, common::kReplaceBadUtf8) + "\n");
}

std::optional<SlurmStudy> ReadSlurmStudy(const std::string& dir) {
  const std::string path = dir + "/slurm/job.json";
  if (!std::filesystem::exists(path)) return std::nullopt;
  const nlohmann::json j = nlohmann::json::parse(ReadText(path), nullptr, false);
  const auto damaged = [&] {
    return std::runtime_error(path + ": damaged (write it again with vmt study sbatch)");
  };
  if (j.is_discarded() || !j.is_object()) throw damaged();
  SlurmStudy s;
  try {
    s.vmt = j.at("vmt").get<std::string>();
    s.scene = j.at("scene").get<std::string>();
    s.dir = j.at("dir").get<std::string>();
    s.shards = j.at("shards").get<int>();
    s.cpus_per_task = j.at("cpus_per_task").get<int>();
    s.repos_options = j.at("repos_options").get<std::vector<std::string>>();
    s.sbatch_options = j.at("sbatch_options").get<std::vector<std::string>>();
  } catch (const nlohmann::json::exception&) {
    throw damaged();
  }
  if (s.shards < 1 || s.cpus_per_task < 1) throw damaged();
  return s;
}

std::vector<int> IncompleteShards(const SlurmStudy& study) {
  std::vector<int> left;
  for (int k = 1; k <= study.shards; ++k)
    if (!ReadStudyProgress(ShardFolder(study, k)).complete()) left.push_back(k);
  return left;
}

// The jobs of the last submission into the folder: "ARRAY MERGE" (ARRAY "-" when only the
// merge was submitted).
std::vector<std::string> LastJobs(const std::string& folder) {
  std::vector<std::string> ids;
  std::istringstream in(ReadText(folder + "/jobs.txt"));
  for (std::string id; in >> id;)
    if (id != "-") ids.push_back(id);
  return ids;
}

SlurmSubmission SubmitSlurmStudy(const SlurmStudy& study, bool submit) {
  SlurmSubmission s;
  const std::string folder = SlurmFolder(study);
  s.shards = IncompleteShards(study);
  const std::vector<std::string> last = LastJobs(folder);
  if (submit && !last.empty()) {
    std::string ids;
    for (const std::string& id : last) ids += (ids.empty() ? "" : ",") + id;
    // Two submissions must never run one shard in one folder at a time. squeue refuses ids
    // it no longer knows: those jobs are long over.
    std::string queued;
    try {
      queued = Run({"squeue", "--noheader", "--jobs=" + ids, "--format=%i %T"});
    } catch (const std::runtime_error&) {
    }
    // With no shard task left and a shard not complete, the last merge waits for a task that
    // failed or was cancelled: it can never run, and the new one replaces it.
    std::string active, stale;
    std::istringstream lines(queued);
    for (std::string line; std::getline(lines, line);) {
      std::istringstream words(line);
      std::string id, state;
      words >> id >> state;
      if (id.empty()) continue;
      if (id == last.back() && state == "PENDING" && !s.shards.empty())
        stale = id;
      else
        active += (active.empty() ? "" : ", ") + id + " " + state;
    }
    if (!active.empty())
      throw std::runtime_error(study.dir + ": its jobs are still queued or running (" + active +
                               "); wait for them, or scancel " + ids + " first");
    if (!stale.empty()) Run({"scancel", stale});
  }
  if (!s.shards.empty()) {
    s.commands.push_back(
        {"sbatch", "--parsable", "--array=" + Joined(s.shards), folder + "/shards.sh"});
    if (submit) s.array_job = JobId(Run(s.commands.back()));
  }
  std::vector<std::string> merge = {"sbatch", "--parsable"};
  if (!s.shards.empty())
    merge.push_back("--dependency=afterok:" + (submit ? s.array_job : std::string("ARRAY_JOB_ID")));
  merge.push_back(folder + "/merge.sh");
  s.commands.push_back(merge);
  if (submit) {
    s.merge_job = JobId(Run(merge));
    common::WriteFileAtomically(
        folder + "/jobs.txt", (s.array_job.empty() ? "-" : s.array_job) + " " + s.merge_job + "\n");
  }
  return s;
}

}  // namespace vmt::sim::study
