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
// Over-aligned types (alignas above the default new alignment, e.g. the contact solver's lanes)
// come through the aligned forms: counted alike.
void* operator new(std::size_t n, std::align_val_t align) {
  if (counting) counted_bytes += n;
  const auto a = static_cast<std::size_t>(align);
  const std::size_t rounded = (n + a - 1) / a * a;  // aligned_alloc takes multiples of `a`
  if (void* p = std::aligned_alloc(a, rounded == 0 ? a : rounded)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p, std::align_val_t /*align*/) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t /*n*/, std::align_val_t /*align*/) noexcept {
  std::free(p);
}
