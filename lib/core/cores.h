// How many cores this process may use.
#pragma once

namespace skinslide {

/// The cores in this thread's CPU affinity mask: what `taskset`, cpusets and farm schedulers that
/// pin a task to some cores allow it. std::thread::hardware_concurrency() counts every online
/// core of the machine instead, so on a farm node shared by several tasks it would start a frame
/// per core of the node, each with its own frame's memory. Falls back to that count where the
/// mask cannot be read. At least 1.
unsigned usable_cores();

}  // namespace skinslide
