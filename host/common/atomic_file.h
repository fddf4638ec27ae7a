#pragma once
// Writing outputs without ever leaving a half-written, clobbered or leftover file behind, even when
// the process is killed.
#include <filesystem>
#include <functional>
#include <memory>

namespace phongcl {

// Calls write(temp) with a path for the new content, then renames it over destination. Where the
// file system supports O_TMPFILE the temporary has no name until that rename (a kill leaves
// nothing); elsewhere it is ".<stem>.tmp<pid><extension>" beside destination, and a later write
// of the same destination removes such temporaries whose process is gone. If write throws, the
// temporary is removed and destination is untouched; the exception propagates.
void write_atomically(const std::filesystem::path& destination,
                      const std::function<void(const std::filesystem::path& temp)>& write);

// The outputs of one run, replaced together: while a batch is alive on this thread,
// write_atomically only writes temporaries, and commit() renames them all after the last one is
// written, so a kill or a failed write never leaves a new PNG beside an old EXR. A batch destroyed
// without commit() discards its temporaries. Batches do not nest.
class AtomicBatch {
 public:
  AtomicBatch();
  ~AtomicBatch();
  AtomicBatch(const AtomicBatch&) = delete;
  AtomicBatch& operator=(const AtomicBatch&) = delete;
  void commit();

  struct Pending;

 private:
  std::unique_ptr<std::vector<Pending>> pending_;
};

}  // namespace phongcl
