#pragma once
#define DEPTHKEY_VERSION "0.1.0"
