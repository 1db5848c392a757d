// Start-up time. Highway 1.0.3 (Debian 12's libhwy) measures its timer's
// resolution in a static initializer of libhwy.so, spinning for about 5 ms
// in every process that links it before main() runs: a third of texproc's
// whole start. texproc never uses Highway's timers (only its target
// dispatch), so the executable interposes the one function that static
// initializer calls (through libhwy's PLT) with one that returns at once.
// Highway 1.0.4 and later take the measurement lazily; this is harmless
// there. bench/bench_process.py shows the effect (--version: 14 -> 8 ms).
#include <cstdint>

namespace hwy::platform {
// The resolution in ticks, as Highway's nanobenchmark would use it: texproc
// measures nothing with it. The symbol is exported from the executable
// (cli/hwy_startup.map), so it takes the place of libhwy's definition.
__attribute__((visibility("default"))) std::uint64_t TimerResolution() { return 1; }
}  // namespace hwy::platform
