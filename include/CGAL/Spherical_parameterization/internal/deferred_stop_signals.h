// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// METIS (through its GKlib) installs its own handler for SIGTERM while one of its functions runs and turns the
// signal into an error return, then puts the previous handler back: a job scheduler's SIGTERM (Slurm, systemd,
// `timeout`) that arrives during a METIS call is lost, and the process runs on, for minutes where METIS is called at
// every Newton step. So the signals that ask a process to stop are blocked in the calling thread around every METIS
// call; one that arrives meanwhile stays pending and reaches the application's own handler (or the default action)
// as soon as the call returns.
// METIS also keeps process-wide state between the start and the end of a call: the handlers it replaces (two calls at
// once on two threads can leave its own handler installed for good) and GKlib's random numbers, which each call seeds
// (orderings made at the same time would depend on the timing). So every METIS call of the package is made through
// Metis_call_guard: one at a time in the process (an application may map several meshes at once on its threads),
// with the stop signals held back. The package makes its METIS calls on the calling thread only: while a call runs,
// METIS' handler (a longjmp to that thread's own context) would be undefined behaviour on any other thread that takes
// the signal.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_DEFERRED_STOP_SIGNALS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_DEFERRED_STOP_SIGNALS_H

#if defined(__unix__) || defined(__APPLE__)
#include <pthread.h>
#include <signal.h>
#define CGAL_SPHERICAL_PARAMETERIZATION_HAS_SIGNAL_MASK 1
#endif

#include <mutex>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// RAII: SIGINT, SIGTERM and SIGHUP are held back in this thread while the object lives.
class Deferred_stop_signals
{
public:
  Deferred_stop_signals()
  {
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_HAS_SIGNAL_MASK
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    sigaddset(&stop, SIGHUP);
    m_blocked = pthread_sigmask(SIG_BLOCK, &stop, &m_previous) == 0;
#endif
  }
  ~Deferred_stop_signals()
  {
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_HAS_SIGNAL_MASK
    if(m_blocked)
      pthread_sigmask(SIG_SETMASK, &m_previous, nullptr);
#endif
  }
  Deferred_stop_signals(const Deferred_stop_signals&) = delete;
  Deferred_stop_signals& operator=(const Deferred_stop_signals&) = delete;

private:
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_HAS_SIGNAL_MASK
  sigset_t m_previous;
  bool m_blocked = false;
#endif
};

// The mutex of the package's METIS calls (one object in the program: a function's static in an inline function).
inline std::mutex& metis_mutex()
{
  static std::mutex mutex;
  return mutex;
}

// RAII around a METIS call: the calls one at a time, the stop signals held back in this thread.
class Metis_call_guard
{
public:
  Metis_call_guard() : m_lock(metis_mutex()) {}
  Metis_call_guard(const Metis_call_guard&) = delete;
  Metis_call_guard& operator=(const Metis_call_guard&) = delete;

private:
  std::lock_guard<std::mutex> m_lock; // taken first: a thread waiting for it can still be stopped
  Deferred_stop_signals m_deferred;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_DEFERRED_STOP_SIGNALS_H
