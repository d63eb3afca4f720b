#pragma once
// GRIP_HD marks a function callable from host and device code: empty in a host build,
// __host__ __device__ when CUDA compiles the same kernel header.
#if defined(__CUDACC__)
#define GRIP_HD __host__ __device__
#else
#define GRIP_HD
#endif
