#pragma once
// The fork-join helper lives in common/ now, for every room's per-frame passes; this name stays while
// packing and launching still include it.
#include "common/host_threads.h"
