#pragma once
// A study's forked processes (workers, a case's copies of the run) end with the process that
// forked them: killed outright (kill -9), a study must not leave them running its cases on.

#include <sys/prctl.h>
#include <unistd.h>

#include <csignal>

namespace vmt::sim::study {

/// Call in the child right after fork(), with the parent's pid taken before it: the kernel
/// kills the child when the parent ends; a parent gone already (before prctl) ends it here.
inline void DieWithParent(pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(1);
}

}  // namespace vmt::sim::study
