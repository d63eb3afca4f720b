// A preload library for the farm's tests: CHOLMOD's symbolic analysis fails, as it does when
// CHOLMOD runs out of memory, so the solver throws in the first trial that factorizes. Loaded
// into one rank only (LD_PRELOAD), it makes a trial fail on that rank.
#include <cstddef>

extern "C" void* cholmod_analyze_p(void*, int*, int*, std::size_t, void*) { return nullptr; }
