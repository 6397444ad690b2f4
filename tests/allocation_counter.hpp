// Counts heap allocations while a scope is armed. The replacement operator
// new (allocation_counter.cpp) serves every test in the binary; it only
// counts while armed, so other tests are unaffected.
#pragma once

#include <cstddef>

namespace depthkey::test {

size_t allocationCount();
// False in sanitizer builds, where operator new belongs to ASan.
bool allocationCounting();

class CountAllocations
{
public:
	CountAllocations();
	~CountAllocations();
	size_t count() const;

private:
	size_t start_;
};

} // namespace depthkey::test
