// A preload library for the farm's tests: the process kills itself (SIGKILL) in its Nth sync of
// the dataset (N from GRIP_KILL_AT_DATASET_SYNC), which a rank makes after writing a work unit's
// rows and done flags and before handing its ids to the journal. Loaded into one rank only
// (LD_PRELOAD), it kills that rank mid-commit.
#include <dlfcn.h>
#include <signal.h>
#include <unistd.h>

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

bool is_dataset(int fd) {
  char link[64];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  char path[PATH_MAX];
  const ssize_t n = ::readlink(link, path, sizeof path - 1);
  return n > 3 && std::strncmp(path + n - 3, ".h5", 3) == 0;
}

}  // namespace

extern "C" int fdatasync(int fd) {
  static int syncs = 0;
  const char* kill_at = std::getenv("GRIP_KILL_AT_DATASET_SYNC");
  if (kill_at != nullptr && is_dataset(fd) && ++syncs == std::atoi(kill_at)) ::raise(SIGKILL);
  using Sync = int (*)(int);
  static const auto real = reinterpret_cast<Sync>(::dlsym(RTLD_NEXT, "fdatasync"));
  return real(fd);
}
