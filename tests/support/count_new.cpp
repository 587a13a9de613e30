// The global operator new and delete of test_snapshot, replaced so that a test can count the
// bytes a piece of code allocates (Snapshot.SnapshotBytesIsWhatACopyAllocates). In a file of its
// own, so that the compiler never sees a `new` and this `free` together (GCC's
// -Wmismatched-new-delete would take the pair for a mismatch).
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

std::atomic<bool> counting{false};          // count while true
std::atomic<std::size_t> counted_bytes{0};  // bytes asked for while counting

void* operator new(std::size_t n) {
  if (counting) counted_bytes += n;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t /*n*/) noexcept {
  std::free(p);
}
