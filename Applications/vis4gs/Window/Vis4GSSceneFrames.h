// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSSceneFrames.h
 * @brief The scene view's CPU frames made off the GUI thread in the application (issue 30).
 *
 * While it exists, the scene view's splat mapper makes its CPU frames on its worker thread
 * (vtkGaussianSplatMapper::AsynchronousFrames), so that neither orbiting nor a pick's
 * highlight waits for the rasteriser on the GUI thread: a render draws the newest finished
 * frame, and each finished frame posts one render of the view to @p context's event loop
 * (several finished before it runs post one). Destroying it clears the mapper's callback
 * (waiting for a call in progress), so nothing is posted afterwards; the frames stay
 * asynchronous.
 */
#ifndef Vis4GSSceneFrames_h
#define Vis4GSSceneFrames_h

#include <atomic>
#include <memory>

class QObject;
class vtkGaussianSceneView;

class Vis4GSSceneFrames
{
public:
  Vis4GSSceneFrames(QObject* context, vtkGaussianSceneView* view);
  ~Vis4GSSceneFrames();
  Vis4GSSceneFrames(const Vis4GSSceneFrames&) = delete;
  Vis4GSSceneFrames& operator=(const Vis4GSSceneFrames&) = delete;

  /// When the frame drawn is not yet the current one (camera, display options), waits for
  /// the worker and renders the view (e.g. before a screenshot).
  void WaitForCurrent();

private:
  vtkGaussianSceneView* View;
  std::shared_ptr<std::atomic<bool>> Posted;
};

#endif
