// Names the first field of a depthkey shared-memory header that is out of
// range, for readers that want to say more than -EPROTO (dk_shm_open only
// says "not a valid ring"). Checks every number before any product, so a
// hostile header cannot overflow the check itself.
#pragma once

#include "hal/depthkey_shm.h"

#include <cstdint>
#include <string>

namespace depthkey {

// "" when the header is consistent with an object of objectSize bytes, else
// e.g. "width = 0 (expected 1..16384)".
std::string shmHeaderFault(const dk_shm_header &header, uint64_t objectSize);

// Maps the object's header read-only and returns shmHeaderFault's answer,
// or why the header could not be read.
std::string shmObjectFault(const char *name);

} // namespace depthkey
