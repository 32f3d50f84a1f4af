#pragma once
// One background thread that runs one job at a time beside the tick loop: the loop starts a
// job, goes on with work of its own, and waits for the job before it uses what the job wrote.
// The thread is started by the constructor (start-up); start() and wait() allocate nothing, so
// the tick loop may use them. A job is a plain function and a pointer, not a std::function
// (which may allocate). Results never depend on thread timing as long as the job and the
// caller touch disjoint data until wait() returns: the caller's part of the contract.
#include <condition_variable>
#include <mutex>
#include <thread>

namespace stereoscout::core {

class Worker {
 public:
  using Job = void (*)(void* context);

  Worker();
  // Waits for a job still running, then stops the thread.
  ~Worker();
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Runs job(context) on the worker thread. The job before must have been waited for
  // (a second start() while one runs is a programming error, checked).
  void start(Job job, void* context);
  // Returns once the job started last has finished (at once if none is running).
  void wait();
  bool busy() const;

 private:
  void run();

  mutable std::mutex mutex_;
  std::condition_variable job_ready_;
  std::condition_variable job_done_;
  Job job_ = nullptr;
  void* context_ = nullptr;
  bool busy_ = false;
  bool stopping_ = false;
  std::thread thread_;  // last: started once the members above exist
};

}  // namespace stereoscout::core
