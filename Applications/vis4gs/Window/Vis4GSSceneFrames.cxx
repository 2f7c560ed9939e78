// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSSceneFrames.h"

#include "vtkGaussianSceneView.h"
#include "vtkGaussianSplatMapper.h"

#include <QMetaObject>
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
  splats->SetFrameReadyCallback(
    [context, view, posted]
    {
      if (!posted->exchange(true))
      {
        QMetaObject::invokeMethod(
          context,
          [view, posted]
          {
            *posted = false;
            view->Render();
          },
          Qt::QueuedConnection);
      }
    });
}

//------------------------------------------------------------------------------
Vis4GSSceneFrames::~Vis4GSSceneFrames()
{
  this->View->GetSplatMapper()->SetFrameReadyCallback(nullptr);
}

//------------------------------------------------------------------------------
void Vis4GSSceneFrames::WaitForCurrent()
{
  vtkGaussianSplatMapper* splats = this->View->GetSplatMapper();
  if (splats->GetFramePending())
  {
    splats->WaitForFrame();
    this->View->Render();
  }
}
