// SPDX-License-Identifier: GPL-3.0-or-later
// The `aquatoria` command: parses the command line, runs one subcommand, maps errors to exit
// codes (0 ok, 1 run/input failure, 2 usage/config error; ARCHITECTURE §7).
#include <fmt/format.h>

#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>

#include "app/commands.hpp"
#include "app/interrupt.hpp"
#include "core/error.hpp"
#include "core/large_pages.hpp"
#ifdef AQ_HAVE_MPI
#include "forest/mpi_session.hpp"
#endif

#ifndef AQ_VERSION
#define AQ_VERSION "dev"
#endif

namespace {

// The signal handlers go in before anything else of the process runs: from the executable's
// .preinit_array, which the dynamic loader calls before the constructors of the shared libraries
// (GDAL, HDF5, PROJ, netCDF, ...: most of the ~40 ms a start takes). A signal while the process
// starts is then reported and ends it with 128 + the signal like any other, instead of killing it
// without a word. (Only the loader's relocations, a few ms, come before.)
void install_handlers_first(int, char**, char**) { aq::app::install_interrupt_handlers(); }
__attribute__((section(".preinit_array"), used)) void (*const kInstallHandlersFirst)(int, char**,
                                                                                     char**) = install_handlers_first;

}  // namespace

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
// The program's operator new (it replaces the library's for the whole process; new[], nothrow new
// and every delete reach this one or free() through the library's): malloc, as the library's,
// and large blocks advised onto transparent huge pages (core/large_pages.hpp). The sanitizers
// bring their own operator new, which this one would hide.
void* operator new(std::size_t bytes) {
  if (bytes == 0) bytes = 1;
  for (;;) {
    if (void* p = std::malloc(bytes)) {
      aq::advise_large_pages(p, bytes);
      return p;
    }
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}
#endif

int main(int argc, char** argv) {
  // Memory the process has had is reused, not given back and faulted afresh. A new page costs
  // the kernel a fault and a clear, and on a virtual machine whose free memory goes back to the
  // host (a balloon) also the host's fault: about 1 GB/s, against 9 GB/s for memory the process
  // frees and takes again. The stages free and allocate lattice bitmaps and mesh tables of
  // hundreds of MB each, so the 15" run faulted in 8.1 GB for a peak of 4.4 GB.
  //  - Large arrays from the heap instead of one mmap each (glibc unmaps an mmapped block when
  //    it is freed): 1.3 million fewer faults on the 1' Mercator run.
  //  - The heap's free top is kept (glibc gives it back above 128 KiB by default).
  //  - One heap for every thread: a block freed on the main thread can serve the UGRID writer's
  //    thread, and a thread's arena, which mmaps anything above 64 MB, is not used for them.
  // The 15" run then faults in 3.7 GB; its peak memory fell from 4.35 to 4.2 GB and its system
  // time from 11-15 s to 4-12 s (huge pages, core/large_pages.hpp, included).
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, -1);  // mallopt(3): -1 turns trimming off
  mallopt(M_ARENA_MAX, 1);
#ifdef AQ_HAVE_MPI
  // Under mpirun every rank starts MPI here; otherwise only a forest run starts it (a singleton).
  if (aq::forest::launched_by_mpirun()) aq::forest::start_mpi(&argc, &argv);
#endif
  aq::app::install_interrupt_handlers();  // again: MPI may have put its own in
  aq::app::Context ctx;
  CLI::App app{"aquatoria: global finite-element ocean meshes and regional orthogonal grids from bathymetry"};
  app.set_version_flag("--version", std::string("aquatoria ") + AQ_VERSION);
  app.require_subcommand(1);
  app.fallthrough();  // -v/-q may follow the subcommand
  bool verbose = false;
  bool quiet = false;
  app.add_flag("-v,--verbose", verbose, "More detail on stderr");
  app.add_flag("-q,--quiet", quiet, "Only warnings and errors on stderr");

  aq::app::add_info_command(app, ctx);
  aq::app::add_mesh_command(app, ctx);
  aq::app::add_regional_command(app, ctx);
  // SUBCOMMANDS: one line each (keep this list in the order of `aquatoria --help`).
  aq::app::add_blocks_command(app, ctx);
  aq::app::add_check_command(app, ctx);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  if (verbose) ctx.log.set_level(aq::LogLevel::kDebug);
  if (quiet) ctx.log.set_level(aq::LogLevel::kWarning);
  // After a failure the process ends with _Exit, past the atexit handlers: HDF5's closes every
  // file it still knows, and a netCDF-4 file whose writing failed on a full disk (already aborted
  // and removed) made it crash with SIGSEGV after the message. Every output was closed or removed
  // while the exception unwound; stdio is flushed here.
  const auto fail = [](int code) {
    std::fflush(nullptr);
    std::_Exit(code);
  };
  int code = 0;
  std::string message;
  bool threw = false;
  try {
    code = ctx.run ? ctx.run() : 2;
  } catch (const aq::Error& e) {
    threw = true;
    code = e.exit_code();
    message = e.what();
  } catch (const std::exception& e) {
    threw = true;
    code = 1;
    message = std::string("internal: ") + e.what();
  }
#ifdef AQ_HAVE_MPI
  // Every rank agrees on the outcome of the lowest failing one; rank 0 prints its message once.
  if (aq::forest::mpi_running()) {
    code = aq::forest::finish_run(code, message);
    if (code != 0) fail(code);
    return 0;
  }
#endif
  if (!threw) return code;
  std::fprintf(stderr, "error: %s\n", message.c_str());
  fail(code);
  return code;
}
