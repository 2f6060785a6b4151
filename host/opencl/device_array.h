#pragma once

#include <algorithm>
#include <vector>

#include "opencl/cl_api.h"

namespace mcquad {

//! A device buffer of `size()` elements of T: sized, read and written in
//! elements, so that no caller does byte arithmetic. OpenCL forbids empty
//! buffers; an empty array holds one unused element.
template <typename T>
class DeviceArray {
 public:
  DeviceArray() = default;
  //! `count` uninitialised elements.
  DeviceArray(const cl::Context& context, size_t count, cl_mem_flags flags = CL_MEM_READ_WRITE)
      : buffer_(context, flags, std::max<size_t>(count, 1) * sizeof(T)), size_(count) {}
  //! Wraps host memory in place (CL_MEM_USE_HOST_PTR): a CPU device reads it
  //! without a copy. The vector must outlive the array and stay unchanged.
  static DeviceArray in_place(const cl::Context& context, const std::vector<T>& host) {
    DeviceArray array;
    array.buffer_ = cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, host.size() * sizeof(T),
                               const_cast<T*>(host.data()));
    array.size_ = host.size();
    return array;
  }

  size_t size() const { return size_; }
  const cl::Buffer& buffer() const { return buffer_; }

  //! Writes all of `host` (host.size() <= size()); blocking or not.
  void write(cl::CommandQueue& queue, const std::vector<T>& host, bool blocking = true) {
    if (!host.empty())
      queue.enqueueWriteBuffer(buffer_, blocking ? CL_TRUE : CL_FALSE, 0, bytes(host.size()), host.data());
  }
  //! Reads the whole array back (blocking).
  std::vector<T> read(cl::CommandQueue& queue) const {
    std::vector<T> host(size_);
    if (!host.empty()) queue.enqueueReadBuffer(buffer_, CL_TRUE, 0, bytes(size_), host.data());
    return host;
  }
  //! Copies `source`'s elements into this array on the device.
  void copy_from(cl::CommandQueue& queue, const DeviceArray& source) {
    if (source.size_ > 0) queue.enqueueCopyBuffer(source.buffer_, buffer_, 0, 0, bytes(source.size_));
  }

  friend void swap(DeviceArray& a, DeviceArray& b) noexcept {
    std::swap(a.buffer_, b.buffer_);
    std::swap(a.size_, b.size_);
  }

 private:
  static size_t bytes(size_t count) { return count * sizeof(T); }
  cl::Buffer buffer_;
  size_t size_ = 0;
};

//! A kernel argument: device arrays pass their buffer, the rest as they are.
template <typename T>
const cl::Buffer& kernel_argument(const DeviceArray<T>& array) {
  return array.buffer();
}
template <typename T>
T kernel_argument(const T& value) {
  return value;  // a copy: scalars and small structs
}

//! Sets every argument of a kernel in order (no hand-numbered indices).
template <typename... Args>
void set_kernel_args(cl::Kernel& kernel, const Args&... args) {
  cl_uint index = 0;
  (kernel.setArg(index++, kernel_argument(args)), ...);
}

}  // namespace mcquad
