/* ff_check.h - (OpenCL only) the device record of the first phase that wrote
 * a NaN or Inf: one int per backend, 0 while all is finite. A kernel that
 * writes a non-finite value stores its tag (phase and substep, see
 * src/sim/nonfinite_log.h) unless an earlier kernel stored one: kernels run
 * in queue order, so the host reads the first failing phase once per step. */
#ifndef FF_CHECK_H
#define FF_CHECK_H
#ifdef __OPENCL_VERSION__
inline void ff_report_nonfinite(__global int* bad, int tag) {
  atomic_cmpxchg((volatile __global int*)bad, 0, tag);
}
#endif
#endif /* FF_CHECK_H */
