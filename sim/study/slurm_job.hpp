#pragma once
// A study on a Slurm cluster: an array job whose task k runs shard k of N into DIR/shards/k,
// and a merge job that waits for it (afterok) and joins the shards into DIR. The scripts are
// plain sbatch files in DIR/slurm/ (to read, or to submit by hand); DIR/slurm/job.json records
// what they were written for, so that submitting again into DIR runs only the shards that are
// not complete, and each of those skips the cases it already holds. Tasks are requeued when a
// node fails (--requeue); a shard whose task was cancelled or failed is left for resubmission.

#include <optional>
#include <string>
#include <vector>

namespace vmt::sim::study {

struct SlurmStudy {
  std::string vmt;    ///< the vmt program the nodes run (absolute; on a shared folder)
  std::string scene;  ///< absolute
  std::string dir;    ///< absolute: the merged study; shards/ and slurm/ inside
  int shards = 1;
  int cpus_per_task = 1;                    ///< each shard's worker processes
  std::vector<std::string> repos_options;   ///< given to each shard's `vmt study repos`
  std::vector<std::string> sbatch_options;  ///< more #SBATCH lines, e.g. --partition=long
};

/// DIR/shards/K.
std::string ShardFolder(const SlurmStudy& study, int k);

/// Writes DIR/slurm/{shards.sh,merge.sh,job.json}.
void WriteSlurmScripts(const SlurmStudy& study);

/// DIR/slurm/job.json; nullopt if there is none. Throws std::runtime_error for a damaged one.
std::optional<SlurmStudy> ReadSlurmStudy(const std::string& dir);

/// The shards whose folders do not hold all their cases yet (1-based, ascending).
std::vector<int> IncompleteShards(const SlurmStudy& study);

struct SlurmSubmission {
  std::vector<int> shards;                         ///< the array's tasks (may be none)
  std::vector<std::vector<std::string>> commands;  ///< the sbatch command lines
  std::string array_job, merge_job;                ///< job ids (when submitted)
};

/// Submits the incomplete shards as one array job and the merge after them (only the merge
/// when every shard is complete). `submit` false: only the commands, nothing is run. Throws
/// std::runtime_error with sbatch's own message when it refuses.
SlurmSubmission SubmitSlurmStudy(const SlurmStudy& study, bool submit);

/// `word` quoted for a POSIX shell.
std::string ShellQuoted(const std::string& word);

}  // namespace vmt::sim::study
