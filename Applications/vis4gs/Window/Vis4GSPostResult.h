// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSPostResult.h
 * @brief A worker thread's result or progress handed to the GUI thread in an order
 * ThreadSanitizer sees.
 *
 * Every worker of the window (document load, score stages, clean-up measurement and fine-tune,
 * comparison load, the scene view's frame and count workers) posts functors to the GUI thread
 * with a queued QMetaObject::invokeMethod. Qt's event queue (and QThread::wait) order the
 * worker's writes before the GUI thread's reads through futexes, which ThreadSanitizer does not
 * see (Qt is not instrumented), so each result read there showed as a race in
 * Scripts/run-sanitizers.sh thread. The functor's last construction, inside invokeMethod after
 * its captures are copied, releases an atomic of its own, which the call acquires before running
 * it, and the call releases it again for the destruction, which may happen in the worker (Qt's
 * reference count decides): the same order, made visible, captures included. (Before, only the
 * writes before the post were; the captures' copies were left to the `race:invokeMethod<`
 * suppression, which matches only while TSan can still restore the copy's stack: after a long score
 * stage it could not, and a progress post was reported.)
 */
#ifndef Vis4GSPostResult_h
#define Vis4GSPostResult_h

#include <QMetaObject>
#include <QObject>

#include <atomic>
#include <type_traits>
#include <utility>

/// A functor whose construction happens before its call, and its call before its destruction,
/// for ThreadSanitizer too: the thread that drops Qt's last reference to the queued call
/// destroys it, which may be the worker, after the GUI thread ran it (Qt's reference count is an
/// atomic of Qt's, unseen as well).
template <class F>
class Vis4GSOrderedCall
{
public:
  explicit Vis4GSOrderedCall(F fn)
    : Fn(std::move(fn))
  {
    this->Stage.store(1, std::memory_order_release);
  }
  Vis4GSOrderedCall(Vis4GSOrderedCall&& other)
    : Fn(std::move(other.Fn))
  {
    this->Stage.store(1, std::memory_order_release);
  }
  ~Vis4GSOrderedCall() { this->Stage.load(std::memory_order_acquire); }
  void operator()()
  {
    this->Stage.load(std::memory_order_acquire);
    this->Fn();
    this->Stage.store(2, std::memory_order_release);
  }

private:
  F Fn;
  std::atomic<int> Stage{ 0 };
};

/// Runs `fn` on `context`'s thread after everything the calling thread wrote so far.
template <class F>
void Vis4GSPostResult(QObject* context, F&& fn)
{
  QMetaObject::invokeMethod(
    context, Vis4GSOrderedCall<std::decay_t<F>>(std::forward<F>(fn)), Qt::QueuedConnection);
}

#endif
