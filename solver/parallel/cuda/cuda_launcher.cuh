#pragma once
// The GPU launcher of the data-parallel engine's stages (solver/parallel/launch.hpp): one CUDA
// thread per item. DeviceArray, a device copy of a host array that frees itself, and
// device_median_ms, the device check's timer. Every CUDA call is checked: a failure throws
// std::runtime_error naming the call and CUDA's message, so that a caller fails its batch's
// environments with a reason rather than reading garbage.
#include <cuda_runtime.h>
#include <thrust/execution_policy.h>
#include <thrust/scan.h>
#include <thrust/sort.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace grip::solver::parallel {

inline void cuda_check(cudaError_t status, const char* call) {
  if (status != cudaSuccess) {
    throw std::runtime_error(std::string(call) + ": " + cudaGetErrorString(status));
  }
}

template <class Stage>
__global__ void run_stage(int count, Stage stage) {
  const int i = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  if (i < count) stage(i);
}

struct CudaLauncher {
  int block = 128;  // threads per block: a tet's 12x12 Hessian keeps many registers busy
  // CG iterations between reads of the running count (block_pcg.hpp, poll_interval): queued
  // without a read between them, an iteration's launches overlap the one before.
  int poll_interval = 8;

  template <class Stage>
  void operator()(int count, const Stage& stage) const {
    if (count == 0) return;
    run_stage<<<(count + block - 1) / block, block>>>(count, stage);
    cuda_check(cudaGetLastError(), "launching a stage");
  }

  template <class T>
  T fetch(const T* value) const {
    T host;
    cuda_check(cudaMemcpy(&host, value, sizeof(T), cudaMemcpyDeviceToHost), "cudaMemcpy a value");
    return host;
  }
  template <class Less>
  void sort(int* items, int count, const Less& less) const {
    thrust::sort(thrust::device, items, items + count, less);
  }
  void exclusive_scan(int* values, int count) const {
    thrust::exclusive_scan(thrust::device, values, values + count, values);
  }
};

template <class T>
class DeviceArray {
 public:
  DeviceArray() = default;
  explicit DeviceArray(std::size_t size) : size_(size) {
    if (size_ > 0) cuda_check(cudaMalloc(&data_, size_ * sizeof(T)), "cudaMalloc");
  }
  explicit DeviceArray(const std::vector<T>& host) : DeviceArray(host.size()) {
    if (size_ > 0) {
      cuda_check(cudaMemcpy(data_, host.data(), size_ * sizeof(T), cudaMemcpyHostToDevice),
                 "cudaMemcpy to the device");
    }
  }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  DeviceArray(DeviceArray&& other) noexcept : data_(other.data_), size_(other.size_) {
    other.data_ = nullptr;
    other.size_ = 0;
  }
  ~DeviceArray() {
    if (data_ != nullptr) cudaFree(data_);
  }

  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  std::vector<T> to_host() const {
    std::vector<T> host(size_);
    if (size_ > 0) {
      cuda_check(cudaMemcpy(host.data(), data_, size_ * sizeof(T), cudaMemcpyDeviceToHost),
                 "cudaMemcpy to the host");
    }
    return host;
  }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

// The median time (ms) of `repeats` runs of `stages` on the device, after one untimed run.
template <class Stages>
double device_median_ms(int repeats, Stages&& stages) {
  cudaEvent_t start, stop;
  cuda_check(cudaEventCreate(&start), "cudaEventCreate");
  cuda_check(cudaEventCreate(&stop), "cudaEventCreate");
  std::vector<float> ms;
  for (int r = 0; r <= repeats; ++r) {
    cuda_check(cudaEventRecord(start), "cudaEventRecord");
    stages();
    cuda_check(cudaEventRecord(stop), "cudaEventRecord");
    cuda_check(cudaEventSynchronize(stop), "running the stages");
    float elapsed = 0.f;
    cuda_check(cudaEventElapsedTime(&elapsed, start, stop), "cudaEventElapsedTime");
    if (r > 0) ms.push_back(elapsed);
  }
  cudaEventDestroy(start);
  cudaEventDestroy(stop);
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

}  // namespace grip::solver::parallel
