#include "tests/allocation_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {

std::atomic<bool> armed{ false };
std::atomic<size_t> allocations{ 0 };

} // namespace

// AddressSanitizer replaces operator new itself and reports a malloc'd block
// freed by its delete as a mismatch: under ASan nothing is counted and the
// allocation test skips (the plain build runs it).
#if !defined(__SANITIZE_ADDRESS__)
namespace {

void *allocate(std::size_t size)
{
	if (armed.load(std::memory_order_relaxed))
		allocations.fetch_add(1, std::memory_order_relaxed);
	if (void *p = std::malloc(size ? size : 1))
		return p;
	throw std::bad_alloc();
}

} // namespace

void *operator new(std::size_t size) { return allocate(size); }
void *operator new[](std::size_t size) { return allocate(size); }
void operator delete(void *p) noexcept { std::free(p); }
void operator delete[](void *p) noexcept { std::free(p); }
void operator delete(void *p, std::size_t) noexcept { std::free(p); }
void operator delete[](void *p, std::size_t) noexcept { std::free(p); }
#endif

bool depthkey::test::allocationCounting()
{
#if defined(__SANITIZE_ADDRESS__)
	return false;
#else
	return true;
#endif
}

namespace depthkey::test {

size_t allocationCount() { return allocations.load(); }

CountAllocations::CountAllocations() : start_(allocations.load()) { armed = true; }
CountAllocations::~CountAllocations() { armed = false; }
size_t CountAllocations::count() const { return allocations.load() - start_; }

} // namespace depthkey::test
