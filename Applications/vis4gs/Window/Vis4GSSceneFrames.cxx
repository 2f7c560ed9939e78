// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSSceneFrames.h"

#include "Vis4GSPostResult.h"

#include "vtkGaussianCameraFrustums.h"
#include "vtkGaussianSceneView.h"
#include "vtkGaussianSplatMapper.h"

#include <QObject>

//------------------------------------------------------------------------------
Vis4GSSceneFrames::Vis4GSSceneFrames(QObject* context, vtkGaussianSceneView* view)
  : View(view)
  , Posted(std::make_shared<std::atomic<bool>>(false))
{
  vtkGaussianSplatMapper* splats = view->GetSplatMapper();
  splats->AsynchronousFramesOn();
  std::shared_ptr<std::atomic<bool>> posted = this->Posted;
  // (Called on the mapper's worker thread: only the queued call touches the view.)
  auto ready = [context, view, posted]
  {
    if (!posted->exchange(true))
    {
      Vis4GSPostResult(context,
        [view, posted]
        {
          *posted = false;
          view->Render();
        });
    }
  };
  splats->SetFrameReadyCallback(ready);
  // A large selection's frustum counts come from the frustums' worker the same way.
  view->GetFrustums()->SetCountsReadyCallback(ready);
}

//------------------------------------------------------------------------------
Vis4GSSceneFrames::~Vis4GSSceneFrames()
{
  this->View->GetSplatMapper()->SetFrameReadyCallback(nullptr);
  this->View->GetFrustums()->SetCountsReadyCallback(nullptr);
}

//------------------------------------------------------------------------------
void Vis4GSSceneFrames::WaitForCurrent()
{
  vtkGaussianSplatMapper* splats = this->View->GetSplatMapper();
  vtkGaussianCameraFrustums* frustums = this->View->GetFrustums();
  if (splats->GetFramePending() || frustums->GetCountsPending())
  {
    splats->WaitForFrame();
    frustums->WaitForCounts();
    this->View->Render();
  }
}
