// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSScoreStages.h"
#include "Vis4GSPostResult.h"

#include "Vis4GSDocument.h"

#include "RemovalEffect.h"

#include "vtkAbstractArray.h"
#include "vtkFieldData.h"
#include "vtkGaussianSession.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <QObject>
#include <QThread>

#include <algorithm>
#include <exception>
#include <utility>

//------------------------------------------------------------------------------
Vis4GSScoreStages::Vis4GSScoreStages(QObject* context)
  : Context(context)
{
}

//------------------------------------------------------------------------------
Vis4GSScoreStages::~Vis4GSScoreStages()
{
  this->Stop();
  this->Wait();
}

//------------------------------------------------------------------------------
void Vis4GSScoreStages::Stop()
{
  if (this->StopFlag)
  {
    *this->StopFlag = true;
  }
}

//------------------------------------------------------------------------------
void Vis4GSScoreStages::Wait()
{
  if (this->Worker)
  {
    this->Worker->wait();
  }
}

//------------------------------------------------------------------------------
void Vis4GSScoreStages::Start(vtkSmartPointer<vtkPolyData> scene,
  vtkSmartPointer<vtkTable> cameras,
  bool images,
  std::shared_ptr<vis4gs::RemovalBaseline> baseline,
  int stages,
  const std::string& name)
{
  if (this->Worker || !scene)
  {
    return;
  }
  auto stop = std::make_shared<std::atomic<bool>>(false);
  this->StopFlag = stop;
  // Without cameras only the needle shape is computed, from the Gaussians alone: exact at once.
  const bool haveCameras = cameras && cameras->GetNumberOfRows() > 0;
  const int of = haveCameras ? 2 : 1;
  const int last = std::max(1, std::min(of, stages));
  this->Worker = QThread::create(
    [this, scene, cameras, images, baseline, stop, of, last, name]
    {
      QString error;
      bool stopped = false;
      for (int k = 1; k <= last; ++k)
      {
        if (stop->load())
        {
          stopped = true;
          break;
        }
        // The filter's ProgressiveStage: 1 is the approximate stage, 0 the settings as given.
        const int filterStage = of == 2 && k == 1 ? 1 : 0;
        const QString message =
          QString("computing the scores, stage %1 of %2%3")
            .arg(k)
            .arg(of)
            .arg(filterStage == 1 ? " (approximate)" : (of == 2 ? " (exact)" : ""));
        Stage stage;
        stage.Number = k;
        stage.Of = of;
        try
        {
          stage.Session = Vis4GSDocument::ComputeScores(
            scene,
            cameras,
            images,
            [this, message](double f, const std::string&)
            {
              Vis4GSPostResult(this->Context,
                [this, f, message]
                {
                  if (this->Progress)
                  {
                    this->Progress(f, message);
                  }
                });
            },
            filterStage == 0 ? baseline.get() : nullptr,
            filterStage,
            stop.get(),
            name);
        }
        catch (const std::exception& e)
        {
          error = QString::fromStdString(e.what());
          break;
        }
        if (!stage.Session)
        {
          stopped = true;
          break;
        }
        if (auto* label = vtkStringArray::SafeDownCast(
              stage.Session->GetGaussiansOutput()->GetFieldData()->GetAbstractArray("ScoreStage")))
        {
          stage.Label = label->GetNumberOfValues() > 0 ? label->GetValue(0) : std::string();
        }
        Vis4GSPostResult(this->Context,
          [this, scene, stage]
          {
            if (this->StageDone)
            {
              this->StageDone(scene, stage);
            }
          });
      }
      Vis4GSPostResult(this->Context,
        [this, scene, error, stopped]
        {
          this->Worker->wait();
          this->Worker->deleteLater();
          this->Worker = nullptr;
          if (this->Finished)
          {
            this->Finished(scene, error, stopped);
          }
        });
    });
  this->Worker->start();
}
