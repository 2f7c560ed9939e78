// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSPostResult.h
 * @brief A worker thread's result handed to the GUI thread in an order ThreadSanitizer sees.
 *
 * Every worker of the window (document load, score stages, clean-up measurement and fine-tune,
 * comparison load) ends by posting a functor to the GUI thread with a queued
 * QMetaObject::invokeMethod. Qt's event queue (and QThread::wait) order the worker's writes
 * before the GUI thread's reads through futexes, which ThreadSanitizer does not see (Qt is not
 * instrumented), so each result read there showed as a race in Scripts/run-sanitizers.sh
 * thread. The worker releases an atomic after its last write and the functor acquires it before
 * running: the same order, made visible. (The functor's own captures, copied inside
 * invokeMethod, are covered by the `race:invokeMethod<` suppression.)
 */
#ifndef Vis4GSPostResult_h
#define Vis4GSPostResult_h

#include <QMetaObject>
#include <QObject>

#include <atomic>
#include <memory>
#include <utility>

/// Runs `fn` on `context`'s thread after everything the calling thread wrote so far.
template <class F>
void Vis4GSPostResult(QObject* context, F&& fn)
{
  auto order = std::make_shared<std::atomic<bool>>(false);
  order->store(true, std::memory_order_release);
  QMetaObject::invokeMethod(
    context,
    [order, fn = std::forward<F>(fn)]() mutable
    {
      order->load(std::memory_order_acquire);
      fn();
    },
    Qt::QueuedConnection);
}

#endif
