/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSession.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianSession.h"

#include "Vis4GSRequestedPort.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkExecutive.h"
#include "vtkGaussianArtifactScoreFilter.h"
#include "vtkGaussianCameraReader.h"
#include "vtkGaussianCompactTree.h"
#include "vtkGaussianFineTuneFilter.h"
#include "vtkGaussianGenealogyTreeFilter.h"
#include "vtkGaussianRemovalEffectFilter.h"
#include "vtkGaussianRuleSelectionFilter.h"
#include "vtkGaussianSceneReader.h"
#include "vtkGaussianStateComparisonFilter.h"
#include "vtkGaussianTrainingLogReader.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkTrivialProducer.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstring>
#include <fstream>
#include <sys/stat.h>
#include <thread>
#include <vector>

vtkStandardNewMacro(vtkGaussianSession);
vtkCxxSetObjectMacro(vtkGaussianSession, SelectedIds, vtkIdTypeArray);

namespace
{
/// Whether @p path ends in .h5 or .hdf5, any case.
bool HasLogExtension(const std::string& path)
{
  std::string tail =
    path.substr(path.find_last_of('.') == std::string::npos ? path.size() : path.find_last_of('.'));
  std::transform(tail.begin(),
    tail.end(),
    tail.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return tail == ".h5" || tail == ".hdf5";
}

/// Whether a string setting must be set: VTK 9.1's vtkSetStdStringFromCharMacro calls Modified()
/// even for the same text, which would make the session's every update re-run the scores.
bool Differs(const char* current, const std::string& wanted)
{
  return wanted != (current ? current : "");
}

/// The text of a VTK error event, without "ERROR: In <source>, line <n>\n<class> (<address>): ":
/// the session names the file itself, the user needs no object address.
std::string MessageText(const char* event)
{
  std::string text = event ? event : "";
  const std::size_t address = text.find("): ");
  if (text.rfind("ERROR: In ", 0) == 0 && address != std::string::npos)
  {
    text = text.substr(address + 3);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
  {
    text.pop_back();
  }
  return text;
}
}

struct vtkGaussianSession::vtkInternals
{
  vtkNew<vtkGaussianTrainingLogReader> Log;
  // The genealogy reads the events through a reader of its own, so that building the tree
  // does not make the snapshot reader forget its snapshot (one port is produced at a time).
  vtkNew<vtkGaussianTrainingLogReader> Events;
  vtkNew<vtkGaussianSceneReader> Scene;
  vtkNew<vtkGaussianCameraReader> Cameras;
  vtkNew<vtkGaussianArtifactScoreFilter> Scores;
  vtkNew<vtkGaussianGenealogyTreeFilter> Genealogy;
  vtkNew<vtkGaussianRuleSelectionFilter> Rule;
  vtkNew<vtkGaussianRemovalEffectFilter> Removal;
  vtkNew<vtkGaussianFineTuneFilter> FineTune;
  vtkNew<vtkGaussianStateComparisonFilter> Comparison;
  vtkNew<vtkTrivialProducer> Given; // SetGaussiansData's Gaussians
  vtkSmartPointer<vtkPolyData> GivenGaussians;
  vtkNew<vtkTrivialProducer> GivenCamerasProducer; // SetCamerasData's cameras
  vtkSmartPointer<vtkTable> GivenCameras;
  vtkNew<vtkTable> NoCameras;
  vtkNew<vtkCallbackCommand> ErrorObserver;
  vtkNew<vtkCallbackCommand> ProgressObserver;
  vtkNew<vtkCallbackCommand> Quiet;
  std::vector<std::string> Errors;
  // The thread running RequestData: the sub-filters' errors and progress are the session's
  // only there. A client may update a sub-filter itself in another thread (the application's
  // genealogy beside the snapshot read); it hears that filter's events, not the session.
  std::atomic<std::thread::id> Executing{};
  // What Connect() connected for (the kind of file is read from its content once per name).
  std::string ConnectedFile;
  // The cameras' producer and port in use (the log reader's port 1, the camera reader, the
  // given table); null: none.
  vtkAlgorithm* CamerasSource = nullptr;
  int CamerasSourcePort = 0;
  vtkAlgorithm* GaussiansSource = nullptr;
  vtkAlgorithm* GaussiansOutput = nullptr;
  // The comparison's second state (CompareFileName), created on first use.
  vtkSmartPointer<vtkGaussianSession> Compared;

  std::vector<vtkAlgorithm*> Algorithms()
  {
    return { this->Log,
      this->Events,
      this->Scene,
      this->Cameras,
      this->Scores,
      this->Genealogy,
      this->Rule,
      this->Removal,
      this->FineTune,
      this->Comparison,
      this->Given,
      this->GivenCamerasProducer };
  }
};

//------------------------------------------------------------------------------
vtkGaussianSession::vtkGaussianSession()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(NumberOfPorts);
  vtkInternals& d = *this->Internals;
  d.ErrorObserver->SetClientData(this->Internals);
  d.ErrorObserver->SetCallback(
    [](vtkObject*, unsigned long, void* client, void* call)
    {
      auto* internals = static_cast<vtkInternals*>(client);
      if (internals->Executing.load() == std::this_thread::get_id())
      {
        internals->Errors.push_back(MessageText(static_cast<char*>(call)));
      }
    });
  d.ProgressObserver->SetClientData(this);
  d.ProgressObserver->SetCallback(
    [](vtkObject* caller, unsigned long, void* client, void*)
    {
      auto* self = static_cast<vtkGaussianSession*>(client);
      if (self->Internals->Executing.load() == std::this_thread::get_id())
      {
        self->UpdateProgress(static_cast<vtkAlgorithm*>(caller)->GetProgress());
      }
    });
  for (vtkAlgorithm* a : d.Algorithms())
  {
    a->AddObserver(vtkCommand::ErrorEvent, d.ErrorObserver);
    a->AddObserver(vtkCommand::ProgressEvent, d.ProgressObserver);
    // "Algorithm ... returned failure": the algorithm's own error, collected above, says why.
    a->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, d.Quiet);
  }
  d.Events->SetLoadSH(false);
  d.Genealogy->SetInputConnection(d.Events->GetOutputPort(3));
  // Cameras of a scene file are optional for what needs no image (coverage, rendering).
  d.Cameras->SetRequireImages(false);
}

//------------------------------------------------------------------------------
vtkGaussianSession* vtkGaussianSession::GetComparedSession()
{
  vtkInternals& d = *this->Internals;
  if (!d.Compared)
  {
    d.Compared = vtkSmartPointer<vtkGaussianSession>::New();
    d.Compared->ComputeScoresOff();
    // Its errors (already naming its file) and progress are this session's while it executes.
    d.Compared->AddObserver(vtkCommand::ErrorEvent, d.ErrorObserver);
    d.Compared->AddObserver(vtkCommand::ProgressEvent, d.ProgressObserver);
    d.Compared->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, d.Quiet);
  }
  return d.Compared;
}

void vtkGaussianSession::SetCompareFileName(const char* name)
{
  const std::string wanted = name ? name : "";
  if (wanted == this->GetCompareFileName())
  {
    return;
  }
  this->GetComparedSession()->SetFileName(wanted.c_str());
  this->Modified();
}

const char* vtkGaussianSession::GetCompareFileName()
{
  return this->Internals->Compared ? this->Internals->Compared->GetFileName() : "";
}

void vtkGaussianSession::SetCompareIteration(int iteration)
{
  if (iteration != this->GetCompareIteration())
  {
    this->GetComparedSession()->SetIteration(iteration);
    this->Modified();
  }
}

int vtkGaussianSession::GetCompareIteration()
{
  return this->Internals->Compared ? this->Internals->Compared->GetIteration() : -1;
}

//------------------------------------------------------------------------------
vtkGaussianSession::~vtkGaussianSession()
{
  this->SetSelectedIds(nullptr);
  delete this->Internals;
}

//------------------------------------------------------------------------------
vtkGaussianTrainingLogReader* vtkGaussianSession::GetLogReader()
{
  return this->Internals->Log;
}
vtkGaussianSceneReader* vtkGaussianSession::GetSceneReader()
{
  return this->Internals->Scene;
}
vtkGaussianCameraReader* vtkGaussianSession::GetCameraReader()
{
  return this->Internals->Cameras;
}
vtkGaussianArtifactScoreFilter* vtkGaussianSession::GetScoreFilter()
{
  return this->Internals->Scores;
}
vtkGaussianGenealogyTreeFilter* vtkGaussianSession::GetGenealogyFilter()
{
  // Connected, so that a client can update it on its own (the application builds the tree in
  // a second thread beside the snapshot read).
  this->Connect();
  return this->Internals->Genealogy;
}
vtkGaussianRuleSelectionFilter* vtkGaussianSession::GetRuleFilter()
{
  return this->Internals->Rule;
}
vtkGaussianRemovalEffectFilter* vtkGaussianSession::GetRemovalEffectFilter()
{
  return this->Internals->Removal;
}
vtkGaussianFineTuneFilter* vtkGaussianSession::GetFineTuneFilter()
{
  this->Connect();
  return this->Internals->FineTune;
}
vtkGaussianStateComparisonFilter* vtkGaussianSession::GetComparisonFilter()
{
  if (this->Connect())
  {
    this->ConnectComparison();
  }
  return this->Internals->Comparison;
}

//------------------------------------------------------------------------------
vtkPolyData* vtkGaussianSession::GetGaussiansOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(GaussiansPort));
}
vtkTable* vtkGaussianSession::GetCamerasOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(CamerasPort));
}
vtkTable* vtkGaussianSession::GetMetricsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(MetricsPort));
}
vtkTable* vtkGaussianSession::GetHistoryOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(HistoryPort));
}
vtkTable* vtkGaussianSession::GetComparisonOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(ComparisonPort));
}
vtkTable* vtkGaussianSession::GetComparisonViewsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(ComparisonViewsPort));
}
vtkTable* vtkGaussianSession::GetRemovalViewsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(RemovalViewsPort));
}
vtkTable* vtkGaussianSession::GetRemovalTotalsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(RemovalTotalsPort));
}
vtkImageData* vtkGaussianSession::GetRemovalPreviewOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(RemovalPreviewPort));
}

//------------------------------------------------------------------------------
void vtkGaussianSession::SetRemovalPreviewView(vtkIdType camera)
{
  // (The filter's MTime is the session's: setting it there re-executes the session.)
  this->Internals->Removal->SetPreviewView(camera);
}
vtkIdType vtkGaussianSession::GetRemovalPreviewView()
{
  return this->Internals->Removal->GetPreviewView();
}

//------------------------------------------------------------------------------
void vtkGaussianSession::SetGaussiansData(vtkPolyData* gaussians)
{
  if (gaussians != this->Internals->GivenGaussians)
  {
    this->Internals->GivenGaussians = gaussians;
    this->Modified();
  }
}
vtkPolyData* vtkGaussianSession::GetGaussiansData()
{
  return this->Internals->GivenGaussians;
}
void vtkGaussianSession::SetCamerasData(vtkTable* cameras)
{
  if (cameras != this->Internals->GivenCameras)
  {
    this->Internals->GivenCameras = cameras;
    this->Modified();
  }
}
vtkTable* vtkGaussianSession::GetCamerasData()
{
  return this->Internals->GivenCameras;
}

//------------------------------------------------------------------------------
void vtkGaussianSession::SetSelectionConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(0, output);
}
void vtkGaussianSession::SetSelectionData(vtkSelection* selection)
{
  this->SetInputDataObject(0, selection);
}

//------------------------------------------------------------------------------
bool vtkGaussianSession::IsTrainingLogFile(const char* path)
{
  static const char signature[8] = { '\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n' };
  std::ifstream in(path ? path : "", std::ios::binary);
  // The superblock is at 0 or, after a user block, at 512, 1024, 2048, ... (HDF5 format §2.1).
  for (std::streamoff offset = 0; in && offset <= (std::streamoff(1) << 20);
       offset = offset == 0 ? 512 : 2 * offset)
  {
    char head[8];
    in.seekg(offset);
    if (!in.read(head, sizeof(head)))
    {
      return false;
    }
    if (std::memcmp(head, signature, sizeof(head)) == 0)
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
bool vtkGaussianSession::IsTrainingLogPath(const char* path)
{
  // A damaged .h5 is a log that cannot be read (the log reader says "not an HDF5 file"), not a
  // scene whose reader complains of a missing PLY header.
  return IsTrainingLogFile(path) || HasLogExtension(path ? path : "");
}

//------------------------------------------------------------------------------
vtkMTimeType vtkGaussianSession::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  for (vtkAlgorithm* a : this->Internals->Algorithms())
  {
    t = std::max(t, a->GetMTime());
  }
  if (this->SelectedIds)
  {
    t = std::max(t, this->SelectedIds->GetMTime());
  }
  if (this->Internals->Compared)
  {
    t = std::max(t, this->Internals->Compared->GetMTime());
  }
  return t;
}

//------------------------------------------------------------------------------
int vtkGaussianSession::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSelection");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkGaussianSession::FillOutputPortInformation(int port, vtkInformation* info)
{
  const char* type = "vtkTable";
  if (port == GaussiansPort)
  {
    type = "vtkPolyData";
  }
  else if (port == RemovalPreviewPort)
  {
    type = "vtkImageData";
  }
  else if (port == TreePort)
  {
    type = "vtkTree";
  }
  info->Set(vtkDataObject::DATA_TYPE_NAME(), type);
  return 1;
}

//------------------------------------------------------------------------------
vtkTypeBool vtkGaussianSession::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inInfo,
  vtkInformationVector* outInfo)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()))
  {
    return this->RequestDataObject(outInfo);
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_NOT_GENERATED()))
  {
    // Only the requested output is produced (as in vtkGaussianTrainingLogReader): showing a
    // snapshot builds no tree.
    vis4gs::MarkOtherPortsNotGenerated(request, outInfo);
    return 1;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, inInfo, outInfo);
  }
  return this->Superclass::ProcessRequest(request, inInfo, outInfo);
}

//------------------------------------------------------------------------------
int vtkGaussianSession::RequestDataObject(vtkInformationVector* outInfo)
{
  for (int port = 0; port < NumberOfPorts; ++port)
  {
    vtkInformation* info = outInfo->GetInformationObject(port);
    vtkDataObject* output = info->Get(vtkDataObject::DATA_OBJECT());
    vtkSmartPointer<vtkDataObject> wanted;
    if (port == GaussiansPort)
    {
      wanted = output && output->IsA("vtkPolyData") ? nullptr : vtkSmartPointer<vtkPolyData>::New();
    }
    else if (port == TreePort)
    {
      // The genealogy filter's compact tree (CompactTree) is passed on as one: a plain vtkTree
      // would not take its flat arrays by a shallow copy.
      const bool compact = this->Internals->Genealogy->GetCompactTree();
      const bool isCompact = output && output->IsA("vtkGaussianCompactTree");
      if (!output || compact != isCompact)
      {
        wanted = compact ? vtkSmartPointer<vtkTree>(vtkSmartPointer<vtkGaussianCompactTree>::New())
                         : vtkSmartPointer<vtkTree>::New();
      }
    }
    else if (port == RemovalPreviewPort)
    {
      wanted =
        output && output->IsA("vtkImageData") ? nullptr : vtkSmartPointer<vtkImageData>::New();
    }
    else if (!output || !output->IsA("vtkTable"))
    {
      wanted = vtkSmartPointer<vtkTable>::New();
    }
    if (wanted)
    {
      info->Set(vtkDataObject::DATA_OBJECT(), wanted);
    }
  }
  return 1;
}

//------------------------------------------------------------------------------
bool vtkGaussianSession::Connect()
{
  vtkInternals& d = *this->Internals;
  // Given Gaussians and cameras need no file (FileName then only names the errors).
  const bool fileNeeded = !(d.GivenGaussians && d.GivenCameras);
  d.CamerasSource = nullptr;
  d.CamerasSourcePort = 0;
  if (fileNeeded && this->FileName.empty())
  {
    d.Errors.push_back("no file name");
    return false;
  }
  // A folder is a scene too (a SOG folder, an INRIA output folder): the scene reader says.
  struct stat st;
  if (fileNeeded &&
    (stat(this->FileName.c_str(), &st) != 0 || !(S_ISREG(st.st_mode) || S_ISDIR(st.st_mode))))
  {
    d.Errors.push_back("no such file");
    return false;
  }
  if (!fileNeeded)
  {
    this->IsTrainingLog = false;
    d.ConnectedFile.clear();
  }
  else if (d.ConnectedFile != this->FileName)
  {
    this->IsTrainingLog = IsTrainingLogPath(this->FileName.c_str());
    d.ConnectedFile = this->FileName;
  }
  if (fileNeeded && this->IsTrainingLog)
  {
    d.Log->SetFileName(this->FileName.c_str());
    d.Events->SetFileName(this->FileName.c_str());
    d.Log->UpdateInformation();
    if (!d.Errors.empty())
    {
      return false; // the log reader's own error (no file, not HDF5) says it all
    }
    const int count = d.Log->GetNumberOfSnapshots();
    if (count == 0)
    {
      d.Errors.push_back("the training log holds no snapshot");
      return false;
    }
    const int nearest = this->Iteration < 0 ? d.Log->GetSnapshotIteration(count - 1)
                                            : d.Log->FindNearestSnapshot(this->Iteration);
    d.Log->SetIteration(nearest);
    if (this->FullSHLimit >= 0)
    {
      d.Log->SetLoadSHRest(d.Log->GetSnapshotSize(nearest) <= this->FullSHLimit);
    }
    d.GaussiansSource = d.Log;
    if (d.Log->HasCameras())
    {
      d.CamerasSource = d.Log;
      d.CamerasSourcePort = 1;
    }
  }
  else if (fileNeeded)
  {
    if (Differs(d.Scene->GetFileName(), this->FileName))
    {
      d.Scene->SetFileName(this->FileName.c_str());
    }
    if (Differs(d.Scene->GetIdProperty(), this->IdProperty))
    {
      d.Scene->SetIdProperty(this->IdProperty.c_str());
    }
    d.GaussiansSource = d.Scene;
    const std::string cameraFile = this->CamerasFileName.empty()
      ? vtkGaussianCameraReader::FindSceneCamerasFile(this->FileName)
      : this->CamerasFileName;
    if (!cameraFile.empty())
    {
      if (Differs(d.Cameras->GetFileName(), cameraFile))
      {
        d.Cameras->SetFileName(cameraFile.c_str());
      }
      d.CamerasSource = d.Cameras;
    }
  }
  if (d.GivenGaussians)
  {
    d.Given->SetOutput(d.GivenGaussians);
    d.GaussiansSource = d.Given;
  }
  if (d.GivenCameras)
  {
    d.GivenCamerasProducer->SetOutput(d.GivenCameras);
    d.CamerasSource = d.GivenCamerasProducer;
    d.CamerasSourcePort = 0;
  }
  if (d.CamerasSource)
  {
    vtkAlgorithmOutput* cameras = d.CamerasSource->GetOutputPort(d.CamerasSourcePort);
    d.Scores->SetCamerasConnection(cameras);
    d.Removal->SetInputConnection(1, cameras);
    d.FineTune->SetCamerasConnection(cameras);
  }
  else
  {
    // No cameras: the scores that need none (the needle shape) still run.
    d.Scores->SetCamerasData(d.NoCameras);
    d.Removal->SetInputData(1, d.NoCameras);
    d.FineTune->SetCamerasData(d.NoCameras);
  }
  if (Differs(d.Scores->GetImageDirectory(), this->ImageDirectory))
  {
    d.Scores->SetImageDirectory(this->ImageDirectory.c_str());
  }
  if (Differs(d.Removal->GetImageDirectory(), this->ImageDirectory))
  {
    d.Removal->SetImageDirectory(this->ImageDirectory.c_str());
  }
  if (Differs(d.FineTune->GetImageDirectory(), this->ImageDirectory))
  {
    d.FineTune->SetImageDirectory(this->ImageDirectory.c_str());
  }
  if (Differs(d.Comparison->GetImageDirectory(), this->ImageDirectory))
  {
    d.Comparison->SetImageDirectory(this->ImageDirectory.c_str());
  }
  d.Scores->SetInputConnection(d.GaussiansSource->GetOutputPort(0));
  vtkAlgorithm* last =
    this->ComputeScores ? static_cast<vtkAlgorithm*>(d.Scores) : d.GaussiansSource;
  if (!this->Rule.empty())
  {
    d.Rule->SetInputConnection(last->GetOutputPort(0));
    if (Differs(d.Rule->GetRule(), this->Rule))
    {
      d.Rule->SetRule(this->Rule.c_str());
    }
    last = d.Rule;
  }
  d.GaussiansOutput = last;
  d.Removal->SetInputConnection(0, last->GetOutputPort(0));
  d.FineTune->SetInputConnection(0, last->GetOutputPort(0));
  d.Comparison->SetInputConnection(0, last->GetOutputPort(0));
  return d.Errors.empty(); // (the log reader's, when the log cannot be opened)
}

//------------------------------------------------------------------------------
bool vtkGaussianSession::ConnectComparison()
{
  vtkInternals& d = *this->Internals;
  if (!d.Compared || d.Compared->FileName.empty())
  {
    return false;
  }
  d.Comparison->SetInputConnection(1, d.Compared->GetOutputPort(GaussiansPort));
  // The cameras, by `vis4gs compare`'s rule: the ones given, a log's own, the compared log's, the
  // cameras.json beside the file.
  vtkAlgorithmOutput* cameras = nullptr;
  std::string file = this->CamerasFileName;
  if (file.empty() && this->IsTrainingLog && d.Log->HasCameras())
  {
    cameras = d.Log->GetOutputPort(1);
  }
  else if (file.empty() && d.Compared->Connect() && d.Compared->IsTrainingLog &&
    d.Compared->Internals->Log->HasCameras())
  {
    cameras = d.Compared->GetOutputPort(CamerasPort);
  }
  else if (file.empty())
  {
    file = vtkGaussianCameraReader::FindSceneCamerasFile(this->FileName);
  }
  if (!file.empty())
  {
    if (Differs(d.Cameras->GetFileName(), file))
    {
      d.Cameras->SetFileName(file.c_str());
    }
    cameras = d.Cameras->GetOutputPort();
  }
  d.Comparison->SetInputConnection(2, cameras);
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianSession::SelectionIds(vtkInformationVector** inInfo, vtkIdTypeArray* ids)
{
  std::vector<vtkIdType> values;
  vtkSelection* selection =
    inInfo[0]->GetNumberOfInformationObjects() > 0 ? vtkSelection::GetData(inInfo[0], 0) : nullptr;
  if (selection)
  {
    for (unsigned int n = 0; n < selection->GetNumberOfNodes(); ++n)
    {
      vtkSelectionNode* node = selection->GetNode(n);
      vtkDataArray* list = vtkDataArray::SafeDownCast(node->GetSelectionList());
      if (node->GetContentType() != vtkSelectionNode::PEDIGREEIDS)
      {
        this->Internals->Errors.push_back(
          "the selection must list GaussianIds as pedigree ids (vtkSelectionNode::PEDIGREEIDS)");
        return false;
      }
      for (vtkIdType i = 0; list && i < list->GetNumberOfTuples(); ++i)
      {
        values.push_back(static_cast<vtkIdType>(list->GetTuple1(i)));
      }
    }
  }
  else if (this->SelectedIds)
  {
    for (vtkIdType i = 0; i < this->SelectedIds->GetNumberOfValues(); ++i)
    {
      values.push_back(this->SelectedIds->GetValue(i));
    }
  }
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  ids->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), ids->GetPointer(0));
  return true;
}

//------------------------------------------------------------------------------
int vtkGaussianSession::RequestData(vtkInformation* request,
  vtkInformationVector** inInfo,
  vtkInformationVector* outInfo)
{
  vtkInternals& d = *this->Internals;
  d.Errors.clear();
  d.Executing = std::this_thread::get_id();
  const int port = vis4gs::RequestedOutputPort(request);
  bool ok = this->Connect();
  for (int p = 0; ok && p < NumberOfPorts; ++p)
  {
    if (port < 0 || p == port)
    {
      ok = this->ProducePort(p, inInfo, outInfo);
    }
  }
  d.Executing = std::thread::id();
  if (!ok)
  {
    std::string text;
    for (const std::string& e : d.Errors)
    {
      text += (text.empty() ? "" : "; ") + e;
    }
    // Named once: a reader's message, or the compared session's, may already start with its file.
    const bool named = text.rfind(this->FileName, 0) == 0 ||
      (d.Compared && !d.Compared->FileName.empty() && text.rfind(d.Compared->FileName, 0) == 0);
    vtkErrorMacro(<< (named ? "" : this->FileName + ": ")
                  << (text.empty() ? "could not be read" : text));
    return 0;
  }
  return 1;
}

//------------------------------------------------------------------------------
bool vtkGaussianSession::ProducePort(int port,
  vtkInformationVector** inInfo,
  vtkInformationVector* outInfo)
{
  vtkInternals& d = *this->Internals;
  vtkDataObject* output = vtkDataObject::GetData(outInfo, port);
  output->Initialize();
  // Updates @p algorithm's @p out and shallow-copies it into this port's output.
  auto pass = [&](vtkAlgorithm* algorithm, int out) -> bool
  {
    const std::size_t before = d.Errors.size();
    if (!algorithm->Update(out, nullptr) || d.Errors.size() > before)
    {
      return false;
    }
    if (vtkDataObject* data = algorithm->GetOutputDataObject(out))
    {
      output->ShallowCopy(data);
    }
    return true;
  };
  const bool log = this->IsTrainingLog;
  switch (port)
  {
    case GaussiansPort:
    {
      if (this->ComputeScores && !this->Rule.empty() && !d.Scores->Update(0, nullptr))
      {
        return false;
      }
      // The rule's "views" are View Coverage times the views the scores used.
      d.Rule->SetNumberOfViews(
        this->ComputeScores ? static_cast<int>(d.Scores->GetNumberOfViewsUsed()) : 0);
      if (!pass(d.GaussiansOutput, 0))
      {
        return false;
      }
      if (!this->Rule.empty() && d.Rule->GetLastRuleError() && *d.Rule->GetLastRuleError())
      {
        d.Errors.push_back(d.Rule->GetLastRuleError());
        return false;
      }
      this->LoadedIteration = log && !d.GivenGaussians ? d.Log->GetLoadedIteration() : -1;
      return true;
    }
    case CamerasPort:
      return d.CamerasSource ? pass(d.CamerasSource, d.CamerasSourcePort) : true;
    case MetricsPort:
      return log && d.Log->HasMetrics() ? pass(d.Log, 2) : true;
    case TreePort:
    case BandsPort:
    {
      const bool built =
        log && d.Log->HasEvents() ? pass(d.Genealogy, port == TreePort ? 0 : 1) : true;
      // The events serve the tree only: their reader lets the file go, so that the log reader
      // holds the one handle of this process, as a log still being written needs to show its
      // new snapshots (vtkGaussianTrainingLogReader::CloseFile).
      d.Events->CloseFile();
      return built;
    }
    case HistoryPort:
    {
      vtkNew<vtkIdTypeArray> ids;
      if (!this->SelectionIds(inInfo, ids))
      {
        return false;
      }
      if (!log || ids->GetNumberOfValues() == 0)
      {
        return true;
      }
      if (this->MaximumHistoryIds > 0 && ids->GetNumberOfValues() > this->MaximumHistoryIds)
      {
        ids->Resize(this->MaximumHistoryIds); // (sorted: the smallest ids stay)
        ids->SetNumberOfValues(this->MaximumHistoryIds);
      }
      return d.Log->GetPropertyHistory(ids, vtkTable::SafeDownCast(output)) != 0;
    }
    case RemovalViewsPort:
    case RemovalTotalsPort:
    case RemovalPreviewPort:
    {
      vtkNew<vtkIdTypeArray> ids;
      if (!this->SelectionIds(inInfo, ids))
      {
        return false;
      }
      if (ids->GetNumberOfValues() == 0)
      {
        return true;
      }
      // The same ids keep the filter's result: a new array would measure the removal again.
      vtkIdTypeArray* current = d.Removal->GetRemovedIds();
      if (!current || current->GetNumberOfValues() != ids->GetNumberOfValues() ||
        !std::equal(ids->GetPointer(0),
          ids->GetPointer(0) + ids->GetNumberOfValues(),
          current->GetPointer(0)))
      {
        d.Removal->SetRemovedIds(ids);
      }
      if (port == RemovalPreviewPort && d.Removal->GetPreviewView() < 0)
      {
        return true;
      }
      return pass(d.Removal, port == RemovalViewsPort ? 0 : (port == RemovalTotalsPort ? 1 : 2));
    }
    case ComparisonPort:
    case ComparisonViewsPort:
      return this->ConnectComparison() ? pass(d.Comparison, port == ComparisonPort ? 0 : 1) : true;
    default:
      return true;
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSession::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Iteration: " << this->Iteration << "\n";
  os << indent << "CamerasFileName: " << this->CamerasFileName << "\n";
  os << indent << "ImageDirectory: " << this->ImageDirectory << "\n";
  os << indent << "IdProperty: " << this->IdProperty << "\n";
  os << indent << "FullSHLimit: " << this->FullSHLimit << "\n";
  os << indent << "ComputeScores: " << this->ComputeScores << "\n";
  os << indent << "Rule: " << this->Rule << "\n";
  os << indent << "CompareFileName: " << this->GetCompareFileName() << "\n";
  os << indent << "CompareIteration: " << this->GetCompareIteration() << "\n";
  os << indent << "SelectedIds: ";
  if (this->SelectedIds)
  {
    os << this->SelectedIds->GetNumberOfValues() << " ids\n";
  }
  else
  {
    os << "(none)\n";
  }
  os << indent << "MaximumHistoryIds: " << this->MaximumHistoryIds << "\n";
  os << indent << "RemovalPreviewView: " << this->Internals->Removal->GetPreviewView() << "\n";
  os << indent << "GaussiansData: " << this->Internals->GivenGaussians.GetPointer() << "\n";
  os << indent << "CamerasData: " << this->Internals->GivenCameras.GetPointer() << "\n";
  os << indent << "IsTrainingLog: " << this->IsTrainingLog << "\n";
  os << indent << "LoadedIteration: " << this->LoadedIteration << "\n";
}
