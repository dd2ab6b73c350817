// `proxima sweep` over MPI ranks. Rank 0 owns DIR: it reads the manifest and sends it to
// every rank, then a server (its main thread, the only one calling MPI) hands out item
// indices one at a time to whichever rank asks — dynamic load balancing, items may differ in
// cost by 100× — while a second thread of rank 0 runs items too. A worker sends each
// finished item packed (sweep/item.h) to rank 0, which stores it and answers with the next
// index. Waits poll with short sleeps: MPI's blocking calls spin, and a spinning idle rank
// would take a core from the ranks still computing.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <unistd.h>

#include "../command.h"
#include "../sweep_ranks.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"

namespace proxima::cli {

namespace {

enum Tag : int { kAsk = 1, kData = 2, kItem = 3 };
constexpr uint64_t kStop = UINT64_MAX;  // kItem payload: no item left
constexpr uint64_t kChunk = 1u << 30;   // bytes per message (MPI counts are int)

void nap() { std::this_thread::sleep_for(std::chrono::milliseconds(1)); }

void wait(MPI_Request& request) {
  for (int done = 0; MPI_Test(&request, &done, MPI_STATUS_IGNORE), !done;) nap();
}

void send_bytes(const std::string& bytes, int to, int tag) {
  for (uint64_t at = 0; at < bytes.size() || at == 0; at += kChunk) {
    const int n = static_cast<int>(std::min<uint64_t>(kChunk, bytes.size() - at));
    MPI_Request r;
    MPI_Isend(bytes.data() + at, n, MPI_BYTE, to, tag, MPI_COMM_WORLD, &r);
    wait(r);
    if (bytes.empty()) break;
  }
}

std::string recv_bytes(uint64_t size, int from, int tag) {
  std::string bytes(size, '\0');
  for (uint64_t at = 0; at < size || at == 0; at += kChunk) {
    const int n = static_cast<int>(std::min<uint64_t>(kChunk, size - at));
    MPI_Request r;
    MPI_Irecv(bytes.data() + at, n, MPI_BYTE, from, tag, MPI_COMM_WORLD, &r);
    wait(r);
    if (size == 0) break;
  }
  return bytes;
}

void send_u64(uint64_t v, int to, int tag) {
  MPI_Request r;
  MPI_Isend(&v, 1, MPI_UINT64_T, to, tag, MPI_COMM_WORLD, &r);
  wait(r);
}

uint64_t recv_u64(int from, int tag) {
  uint64_t v = 0;
  MPI_Request r;
  MPI_Irecv(&v, 1, MPI_UINT64_T, from, tag, MPI_COMM_WORLD, &r);
  wait(r);
  return v;
}

// Rank 0's manifest text (or its error, then every rank stops) on every rank.
struct Shared {
  std::string error, manifest, base_dir;
};

void broadcast(std::string& s) {
  uint64_t n = s.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  s.resize(n);
  if (n) MPI_Bcast(s.data(), static_cast<int>(n), MPI_BYTE, 0, MPI_COMM_WORLD);
}

sweep::Manifest shared_manifest(const SweepRun& run, int rank) {
  Shared s;
  if (rank == 0) try {
      prepare_out_dir(run.out);
      sweep::read_manifest(run.manifest);  // checks it before any rank starts
      std::FILE* f = std::fopen(run.manifest.c_str(), "rb");
      for (int c; f && (c = std::fgetc(f)) != EOF;) s.manifest.push_back(static_cast<char>(c));
      if (f) std::fclose(f);
      s.base_dir = std::filesystem::path(run.manifest).parent_path().string();
    } catch (const InputError& e) {
      s.error = e.what();
    }
  broadcast(s.error);
  if (!s.error.empty()) throw InputError(rank == 0 ? s.error : "");
  broadcast(s.manifest);
  broadcast(s.base_dir);
  return sweep::parse_manifest(s.manifest, s.base_dir, run.manifest);
}

// A rank's scratch directory, on its own node.
std::filesystem::path scratch_dir(int rank) {
  return std::filesystem::temp_directory_path() /
         ("proxima-sweep-" + std::to_string(::getpid()) + "-" + std::to_string(rank));
}

// A rank > 0: ask, run, send back, until told to stop.
void worker(const sweep::Manifest& m, int rank) {
  const std::filesystem::path scratch = scratch_dir(rank);
  send_u64(kStop, 0, kAsk);  // nothing finished yet
  for (uint64_t i; (i = recv_u64(0, kItem)) != kStop;) {
    std::vector<std::string> inputs;
    for (auto& file : sweep::unpack_item(recv_bytes(recv_u64(0, kItem), 0, kItem)).files)
      inputs.push_back(std::move(file.second));
    const std::string packed = sweep::pack_item(sweep::run_item(m.items.at(i), scratch, inputs));
    send_u64(i, 0, kAsk);
    send_u64(packed.size(), 0, kData);
    send_bytes(packed, 0, kData);
  }
  std::error_code ec;
  std::filesystem::remove_all(scratch, ec);
}

// Sends item `i` and its inputs' photo.bin or part.bin bytes (packed as files "0", "1", …) to `to`.
void send_item(const sweep::SweepCoordinator& c, size_t i, int to) {
  sweep::ItemFiles inputs;
  for (std::string& bytes : c.inputs(i)) inputs.files.emplace_back(std::to_string(inputs.files.size()), std::move(bytes));
  const std::string packed = sweep::pack_item(inputs);
  send_u64(i, to, kItem);
  send_u64(packed.size(), to, kItem);
  send_bytes(packed, to, kItem);
}

// Rank 0's server: answers every rank's asks until each was told to stop. A rank asking
// while the items left wait for inputs still running waits for an answer until one is ready.
void serve(sweep::SweepCoordinator& c, std::mutex& lock, int ranks) {
  std::vector<int> parked;
  for (int stopped = 0; stopped < ranks - 1;) {
    // Parked ranks first: an item finished since may have made one ready.
    while (!parked.empty()) {
      std::optional<size_t> next;
      bool handed_out = false;
      {
        const std::lock_guard<std::mutex> g(lock);
        next = c.next();
        handed_out = c.handed_out();
      }
      if (!next && !handed_out) break;
      const int to = parked.back();
      parked.pop_back();
      if (next) {
        send_item(c, *next, to);
      } else {
        send_u64(kStop, to, kItem);
        ++stopped;
      }
    }
    int ready = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kAsk, MPI_COMM_WORLD, &ready, &status);
    if (!ready) {
      nap();
      continue;
    }
    const int from = status.MPI_SOURCE;
    const uint64_t finished = recv_u64(from, kAsk);
    if (finished != kStop) {
      const std::string packed = recv_bytes(recv_u64(from, kData), from, kData);
      const std::lock_guard<std::mutex> g(lock);
      c.finish(finished, sweep::unpack_item(packed), from);
    }
    parked.push_back(from);
  }
}

// Rank 0: the server on this thread, items on a second one.
int coordinate(const SweepRun& run, const sweep::Manifest& m, int ranks) {
  const std::filesystem::path out(run.out);
  sweep::SweepCoordinator c(m, out, stderr);
  std::mutex lock;
  std::exception_ptr failure;
  std::thread local([&] {
    try {
      const std::filesystem::path scratch = scratch_dir(0);
      for (;;) {
        std::optional<size_t> i;
        std::vector<std::string> inputs;
        bool handed_out = false;
        {
          const std::lock_guard<std::mutex> g(lock);
          i = c.next();
          if (i) inputs = c.inputs(*i);
          handed_out = c.handed_out();
        }
        if (!i && handed_out) break;
        if (!i) {  // the items left wait for inputs other ranks are running
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
          continue;
        }
        sweep::ItemFiles files = sweep::run_item(m.items[*i], scratch, inputs);
        const std::lock_guard<std::mutex> g(lock);
        c.finish(*i, files, 0);
      }
      std::filesystem::remove_all(scratch);
    } catch (...) {
      failure = std::current_exception();
    }
  });
  try {
    serve(c, lock, ranks);
  } catch (const std::exception& e) {  // DIR not writable, a broken transport: nothing to save
    std::fprintf(stderr, "proxima: sweep rank 0: internal error: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  local.join();
  if (failure) std::rethrow_exception(failure);
  return report_sweep(out, sweep::merge_sweep(m, out, run.command));
}

// --threads 0: this node's cores shared by the ranks on it.
int threads_per_rank(int threads) {
  if (threads > 0) return threads;
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int local = 1;
  MPI_Comm_size(node, &local);
  MPI_Comm_free(&node);
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  return std::max(1, cores / std::max(1, local));
}

// Every rank leaves together, sleeping while it waits (MPI_Finalize alone may spin).
void leave() {
  MPI_Request r;
  MPI_Ibarrier(MPI_COMM_WORLD, &r);
  wait(r);
}

}  // namespace

int run_sweep_ranks(const SweepRun& run) {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int code = 0;
  try {
    const sweep::Manifest m = shared_manifest(run, rank);
    ThreadLimit limit(threads_per_rank(run.threads));
    if (rank == 0) {
      std::fprintf(stderr, "sweep: %d ranks, %d threads each\n", ranks, active_threads());
      code = coordinate(run, m, ranks);
    } else {
      worker(m, rank);
    }
    leave();
  } catch (const InputError& e) {
    // Rank 0 read bad input before any work, and every rank learnt it: all stop, exit 2.
    if (rank == 0) std::fprintf(stderr, "proxima: %s\n", e.what());
    MPI_Finalize();
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "proxima: sweep rank %d: internal error: %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return code;
}

}  // namespace proxima::cli
