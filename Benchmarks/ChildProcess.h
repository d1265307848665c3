// SPDX-License-Identifier: BSD-3-Clause
// Runs one benchmark case in a child process, so that its peak resident
// memory is its own and a crash ends only that case.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <type_traits>

namespace volrad::bench {

struct ChildResult
{
  bool finished = false; ///< the child handed its result back
  int status = 0;        ///< its wait status
  double peakMiB = 0.0;  ///< its peak resident memory
};

/// out = f() computed in a child (T trivially copyable, sent through a pipe).
template<class T, class F>
ChildResult runInChild(F&& f, T& out)
{
  static_assert(std::is_trivially_copyable_v<T>, "the result crosses a pipe");
  ChildResult r;
  int pipefd[2];
  if (pipe(pipefd) != 0) {
    return r;
  }
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid < 0) {
    close(pipefd[0]);
    close(pipefd[1]);
    return r;
  }
  if (pid == 0) {
    close(pipefd[0]);
    const T result = f();
    const bool ok = write(pipefd[1], &result, sizeof(result)) == sizeof(result);
    _exit(ok ? 0 : 1);
  }
  close(pipefd[1]);
  r.finished = read(pipefd[0], &out, sizeof(out)) == sizeof(out);
  close(pipefd[0]);
  struct rusage usage;
  wait4(pid, &r.status, 0, &usage);
  r.peakMiB = usage.ru_maxrss / 1024.0;
  return r;
}

} // namespace volrad::bench
