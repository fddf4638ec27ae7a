#include "common/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "common/error.h"

namespace phongcl {

namespace fs = std::filesystem;

// A new file's content: an unnamed O_TMPFILE inode (fd >= 0) or a named temporary.
struct AtomicBatch::Pending {
  fs::path destination;
  int fd = -1;
  fs::path named;  // the temporary's name once it has one
};

namespace {

thread_local std::vector<AtomicBatch::Pending>* current_batch = nullptr;

fs::path directory_of(const fs::path& destination) {
  return destination.parent_path().empty() ? fs::path(".") : destination.parent_path();
}

// Room for the pid (up to 7 digits on Linux, 10 allowed) in a temporary's name.
constexpr std::size_t kPidDigits = 10;

std::size_t name_max(const fs::path& directory) {
  const long limit = ::pathconf(directory.c_str(), _PC_NAME_MAX);
  return limit > 0 ? static_cast<std::size_t>(limit) : 255;
}

// The temporary keeps the destination's extension: some writers look at it. Its name must fit
// wherever the destination's does: a stem too long for ".<stem>.tmp<pid><ext>" is cut, and a hash
// of the whole stem keeps two long names with one beginning apart.
std::string temp_prefix(const fs::path& destination) {
  const std::string stem = destination.stem().string(), extension = destination.extension().string();
  const std::size_t fixed = 1 + 4 + kPidDigits + extension.size();  // ".", ".tmp", pid, extension
  const std::size_t limit = name_max(directory_of(destination));
  std::string prefix(1, '.');  // appends, not "." + stem: GCC 12 warns a false -Wrestrict on that
  if (fixed + stem.size() <= limit) {
    prefix += stem;
  } else {
    char hash[20];
    std::snprintf(hash, sizeof hash, "~%016zx", std::hash<std::string>{}(stem));
    const std::size_t room = limit > fixed + std::strlen(hash) ? limit - fixed - std::strlen(hash) : 0;
    prefix += stem.substr(0, room);
    prefix += hash;
  }
  prefix += ".tmp";
  return prefix;
}

// A writer's message names the temporary it was given ("/proc/self/fd/5"); the user knows the
// destination.
std::string with_destination(std::string message, const fs::path& temp, const fs::path& destination) {
  const std::string from = temp.string(), to = destination.string();
  for (std::size_t at = message.find(from); at != std::string::npos; at = message.find(from, at + to.size()))
    message.replace(at, from.size(), to);
  return message;
}

fs::path named_temp(const fs::path& destination) {
  return directory_of(destination) /
         (temp_prefix(destination) + std::to_string(::getpid()) + destination.extension().string());
}

fs::path fd_path(int fd) { return "/proc/self/fd/" + std::to_string(fd); }

// Temporaries of destination left by processes that no longer exist (killed mid-write).
void remove_stale_temporaries(const fs::path& destination) {
  const std::string prefix = temp_prefix(destination), extension = destination.extension().string();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory_of(destination), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() + extension.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
      continue;
    const std::string pid = name.substr(prefix.size(), name.size() - prefix.size() - extension.size());
    if (pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
    if (::kill(static_cast<pid_t>(std::stol(pid)), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
    std::error_code ignored;
    fs::remove(entry.path(), ignored);
  }
}

// An unnamed file in destination's directory that writers can open by path, or -1 where the file
// system (or a missing /proc) does not allow it.
int open_unnamed(const fs::path& destination) {
  const int fd = ::open(directory_of(destination).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd < 0) return -1;
  if (::access(fd_path(fd).c_str(), W_OK) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

void discard(AtomicBatch::Pending& pending) {
  if (pending.fd >= 0) ::close(pending.fd);
  pending.fd = -1;
  std::error_code ignored;
  if (!pending.named.empty()) fs::remove(pending.named, ignored);
  pending.named.clear();
}

AtomicBatch::Pending write_temporary(const fs::path& destination, const std::function<void(const fs::path&)>& write) {
  remove_stale_temporaries(destination);
  AtomicBatch::Pending pending{destination, open_unnamed(destination), {}};
  const fs::path temp = pending.fd >= 0 ? fd_path(pending.fd) : named_temp(destination);
  if (pending.fd < 0) pending.named = temp;
  try {
    write(temp);
  } catch (const std::exception& error) {
    discard(pending);
    const std::string message = error.what();
    if (message.find(temp.string()) == std::string::npos) throw;
    throw InputError(with_destination(message, temp, destination));
  } catch (...) {
    discard(pending);
    throw;
  }
  return pending;
}

// Names every unnamed temporary first (the only step that can fail for lack of space or a too long
// name), then renames them all. The files they replace are held open until every rename is done:
// the last reference to a replaced file frees its blocks, 2-8 ms for a 1080p EXR on ext4, and done
// inside a rename it let a kill find the other outputs' temporaries named, beside a mix of old and
// new files. Held, the renames take microseconds and the freeing happens after them.
void commit_all(std::vector<AtomicBatch::Pending>& all) {
  std::vector<int> replaced;
  for (const auto& pending : all) replaced.push_back(::open(pending.destination.c_str(), O_PATH | O_CLOEXEC));
  struct CloseReplaced {
    std::vector<int>& fds;
    ~CloseReplaced() {
      for (int fd : fds)
        if (fd >= 0) ::close(fd);
    }
  } close_replaced{replaced};
  for (auto& pending : all) {
    if (pending.fd < 0) continue;
    pending.named = named_temp(pending.destination);
    std::error_code ignored;
    fs::remove(pending.named, ignored);  // a leftover of an earlier process with our pid
    if (::linkat(AT_FDCWD, fd_path(pending.fd).c_str(), AT_FDCWD, pending.named.c_str(), AT_SYMLINK_FOLLOW) != 0) {
      const std::string problem = std::strerror(errno);
      pending.named.clear();
      throw InputError(pending.destination, "cannot write: " + problem);
    }
    ::close(pending.fd);
    pending.fd = -1;
  }
  for (auto& pending : all) {
    std::error_code ec;
    fs::rename(pending.named, pending.destination, ec);
    if (ec) throw InputError(pending.destination, "cannot write: " + ec.message());
    pending.named.clear();
  }
}

}  // namespace

void write_atomically(const fs::path& destination, const std::function<void(const fs::path&)>& write) {
  AtomicBatch::Pending pending = write_temporary(destination, write);
  if (current_batch != nullptr) {
    current_batch->push_back(std::move(pending));
    return;
  }
  std::vector<AtomicBatch::Pending> one{std::move(pending)};
  try {
    commit_all(one);
  } catch (...) {
    discard(one.front());
    throw;
  }
}

AtomicBatch::AtomicBatch() : pending_(std::make_unique<std::vector<Pending>>()) {
  if (current_batch != nullptr) throw std::logic_error("AtomicBatch: batches do not nest");
  current_batch = pending_.get();
}

AtomicBatch::~AtomicBatch() {
  if (current_batch == pending_.get()) current_batch = nullptr;
  for (auto& pending : *pending_) discard(pending);
}

void AtomicBatch::commit() {
  current_batch = nullptr;
  commit_all(*pending_);
  pending_->clear();
}

}  // namespace phongcl
