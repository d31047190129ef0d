// parallel_grain.h - how much work an OpenMP loop needs before it runs on
// several threads. A parallel region costs a fork, a join and a barrier:
// microseconds with 2 threads on a quiet machine, a scheduler time slice when
// a thread is descheduled on a busy one. Loops of light iterations (a few
// dozen flops, no neighbour search) stay on one thread below this many
// iterations: the clusters' mean velocities, the metrics' sums over a small
// fluid. Measured with `flowform bench --table1 --threads 2` (bunny): running
// the shape-matching loops over ~3k control particles on one thread as well
// saved much on an overloaded machine but cost ~0.15 ms per step on a
// moderately loaded one, so they stay parallel at that size.
#pragma once

namespace ff {

constexpr long kParallelLightLoop = 2048;

}  // namespace ff
