/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSDataModel.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "Vis4GSDataModel.h"

#include "GaussianMath.h"

#include "vtkCharArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkShortArray.h"
#include "vtkSignedCharArray.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedIntArray.h"
#include "vtkUnsignedShortArray.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <set>
#include <unordered_map>
#include <unordered_set>

namespace vis4gs
{
namespace detail
{
namespace
{
// The owners of adopted buffers by address. VTK's free function is a plain function pointer
// with no client data, hence the table. Never destroyed: arrays may be freed at exit.
struct AdoptedBuffers
{
  std::mutex Mutex;
  std::unordered_map<void*, std::shared_ptr<void>> Owners;
  // The buffers whose owner is a shared GaussianCloud (their vectors), for SharedGaussianCloud.
  std::unordered_set<const void*> CloudBuffers;
};
AdoptedBuffers& Adopted()
{
  static auto* buffers = new AdoptedBuffers;
  return *buffers;
}
void ReleaseAdopted(void* data)
{
  std::shared_ptr<void> owner;
  {
    std::lock_guard<std::mutex> lock(Adopted().Mutex);
    auto it = Adopted().Owners.find(data);
    if (it == Adopted().Owners.end())
    {
      return;
    }
    owner = std::move(it->second);
    Adopted().Owners.erase(it);
    Adopted().CloudBuffers.erase(data);
  }
  // owner (the vector) is freed here, outside the lock.
}
}

void (*AdoptBuffer(void* data, std::shared_ptr<void> owner))(void*)
{
  std::lock_guard<std::mutex> lock(Adopted().Mutex);
  Adopted().Owners[data] = std::move(owner);
  return &ReleaseAdopted;
}

namespace
{
// AdoptBuffer for a buffer that is a vector of the shared cloud @p owner.
void (*AdoptCloudBuffer(void* data, std::shared_ptr<GaussianCloud> owner))(void*)
{
  std::lock_guard<std::mutex> lock(Adopted().Mutex);
  Adopted().Owners[data] = std::move(owner);
  Adopted().CloudBuffers.insert(data);
  return &ReleaseAdopted;
}

// The shared cloud owning @p data, or null.
std::shared_ptr<const GaussianCloud> FindCloudOf(const void* data)
{
  std::lock_guard<std::mutex> lock(Adopted().Mutex);
  if (!data || !Adopted().CloudBuffers.count(data))
  {
    return nullptr;
  }
  auto it = Adopted().Owners.find(const_cast<void*>(data));
  return it == Adopted().Owners.end() ? nullptr
                                      : std::static_pointer_cast<const GaussianCloud>(it->second);
}
}
}

namespace
{
constexpr int MaxDistortion = 12;

//------------------------------------------------------------------------------
// A VTK array named @p name whose memory is @p values, a non-empty vector of the shared cloud
// @p owner (which lives while the array does).
template <typename ArrayT, typename T>
vtkSmartPointer<ArrayT> ShareVector(const char* name,
  std::vector<T>& values,
  int components,
  const std::shared_ptr<GaussianCloud>& owner)
{
  using V = typename ArrayT::ValueType;
  static_assert(sizeof(V) == sizeof(T) && std::is_integral<V>::value == std::is_integral<T>::value,
    "the array's value type must have the vector's representation");
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  V* data = reinterpret_cast<V*>(values.data());
  array->SetArray(
    data, static_cast<vtkIdType>(values.size()), 0, vtkAbstractArray::VTK_DATA_ARRAY_USER_DEFINED);
  array->SetArrayFreeFunction(detail::AdoptCloudBuffer(data, owner));
  return array;
}

//------------------------------------------------------------------------------
// A float array of @p values: the memory of @p shared's vector when @p shared is the cloud
// being filled from (no copy), else a copy.
vtkSmartPointer<vtkFloatArray> MakeFloatArray(const char* name,
  int components,
  std::vector<float>& values,
  const std::shared_ptr<GaussianCloud>& shared)
{
  if (shared)
  {
    return ShareVector<vtkFloatArray>(name, values, components, shared);
  }
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  if (!values.empty())
  {
    std::memcpy(a->GetPointer(0), values.data(), values.size() * sizeof(float));
  }
  return a;
}

//------------------------------------------------------------------------------
// Copies a named array into @p out; false with a message when its component count is wrong.
bool FetchFloats(vtkPointData* pd,
  const char* name,
  int components,
  std::size_t count,
  std::vector<float>& out,
  std::string* error)
{
  vtkDataArray* a = pd->GetArray(name);
  if (!a)
  {
    out.clear();
    return true;
  }
  if ((components > 0 && a->GetNumberOfComponents() != components) ||
    static_cast<std::size_t>(a->GetNumberOfTuples()) != count)
  {
    if (error)
    {
      *error = std::string("array '") + name + "' has " +
        std::to_string(a->GetNumberOfComponents()) + " components and " +
        std::to_string(a->GetNumberOfTuples()) + " tuples; expected " + std::to_string(components) +
        " components and " + std::to_string(count) + " tuples";
    }
    return false;
  }
  const std::size_t n = count * static_cast<std::size_t>(a->GetNumberOfComponents());
  out.resize(n);
  if (auto* f = vtkFloatArray::SafeDownCast(a))
  {
    if (n)
    {
      std::memcpy(out.data(), f->GetPointer(0), n * sizeof(float));
    }
  }
  else
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      out[i] = static_cast<float>(a->GetVariantValue(static_cast<vtkIdType>(i)).ToDouble());
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool ScalarTypeFromVTK(int vtkType, ScalarType& type)
{
  switch (vtkType)
  {
    case VTK_SIGNED_CHAR:
    case VTK_CHAR:
      type = ScalarType::Int8;
      return true;
    case VTK_UNSIGNED_CHAR:
      type = ScalarType::UInt8;
      return true;
    case VTK_SHORT:
      type = ScalarType::Int16;
      return true;
    case VTK_UNSIGNED_SHORT:
      type = ScalarType::UInt16;
      return true;
    case VTK_INT:
      type = ScalarType::Int32;
      return true;
    case VTK_UNSIGNED_INT:
      type = ScalarType::UInt32;
      return true;
    case VTK_FLOAT:
      type = ScalarType::Float32;
      return true;
    case VTK_DOUBLE:
      type = ScalarType::Float64;
      return true;
    default:
      return false;
  }
}
}

//------------------------------------------------------------------------------
vtkDataArray* NewArrayFromExtra(const ExtraProperty& extra)
{
  vtkDataArray* a = nullptr;
  switch (extra.Type)
  {
    case ScalarType::Int8:
      a = vtkSignedCharArray::New();
      break;
    case ScalarType::UInt8:
      a = vtkUnsignedCharArray::New();
      break;
    case ScalarType::Int16:
      a = vtkShortArray::New();
      break;
    case ScalarType::UInt16:
      a = vtkUnsignedShortArray::New();
      break;
    case ScalarType::Int32:
      a = vtkIntArray::New();
      break;
    case ScalarType::UInt32:
      a = vtkUnsignedIntArray::New();
      break;
    case ScalarType::Float32:
      a = vtkFloatArray::New();
      break;
    case ScalarType::Float64:
      a = vtkDoubleArray::New();
      break;
  }
  const std::size_t size = ScalarTypeSize(extra.Type);
  a->SetName(extra.Name.c_str());
  a->SetNumberOfComponents(1);
  a->SetNumberOfTuples(static_cast<vtkIdType>(extra.Bytes.size() / size));
  if (!extra.Bytes.empty())
  {
    std::memcpy(a->GetVoidPointer(0), extra.Bytes.data(), extra.Bytes.size());
  }
  return a;
}

namespace
{
//------------------------------------------------------------------------------
// GaussianCloudToPolyData; when @p shared (then @p cloud is *shared) the arrays are the vectors
// of @p cloud, otherwise @p cloud is only read.
void FillPolyData(GaussianCloud& cloud,
  vtkPolyData* output,
  const PolyDataOptions& options,
  const std::shared_ptr<GaussianCloud>& shared)
{
  output->Initialize();
  const std::size_t n = cloud.Count;

  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  if (cloud.Positions.size() == 3 * n && n > 0)
  {
    points->SetData(MakeFloatArray(nullptr, 3, cloud.Positions, shared));
  }
  else
  {
    points->SetNumberOfPoints(static_cast<vtkIdType>(n));
  }
  output->SetPoints(points);

  vtkPointData* pd = output->GetPointData();
  vtkSmartPointer<vtkIdTypeArray> ids;
  if (shared && n > 0)
  {
    if (cloud.Ids.size() != n)
    {
      cloud.Ids.resize(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        cloud.Ids[i] = static_cast<std::int64_t>(i);
      }
    }
    ids = ShareVector<vtkIdTypeArray>(arrays::GaussianId, cloud.Ids, 1, shared);
  }
  else
  {
    ids = vtkSmartPointer<vtkIdTypeArray>::New();
    ids->SetName(arrays::GaussianId);
    ids->SetNumberOfTuples(static_cast<vtkIdType>(n));
    for (std::size_t i = 0; i < n; ++i)
    {
      ids->SetValue(static_cast<vtkIdType>(i), static_cast<vtkIdType>(cloud.GetId(i)));
    }
  }
  pd->SetPedigreeIds(ids);

  const bool hasOpacity = cloud.OpacityLogits.size() == n;
  std::vector<float> opacity, scale;
  if (options.ActivatedArrays)
  {
    if (hasOpacity)
    {
      opacity.resize(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        opacity[i] = Sigmoid(cloud.OpacityLogits[i]);
      }
    }
    if (cloud.LogScales.size() == 3 * n)
    {
      scale.resize(3 * n);
      for (std::size_t i = 0; i < 3 * n; ++i)
      {
        scale[i] = ActivatedScale(cloud.LogScales[i]);
      }
    }
  }

  if (cloud.LogScales.size() == 3 * n)
  {
    pd->AddArray(MakeFloatArray(arrays::LogScale, 3, cloud.LogScales, shared));
  }
  if (cloud.Rotations.size() == 4 * n)
  {
    pd->AddArray(MakeFloatArray(arrays::Rotation, 4, cloud.Rotations, shared));
  }
  if (hasOpacity)
  {
    pd->AddArray(MakeFloatArray(arrays::OpacityLogit, 1, cloud.OpacityLogits, shared));
  }
  const int shComponents = 3 * cloud.ShCoefficientCount();
  if (n > 0 && cloud.SH.size() == n * static_cast<std::size_t>(shComponents))
  {
    pd->AddArray(MakeFloatArray(arrays::SH, shComponents, cloud.SH, shared));
  }

  if (options.ActivatedArrays && hasOpacity)
  {
    pd->AddArray(AdoptVector<vtkFloatArray>(arrays::Opacity, std::move(opacity)));
  }
  if (options.ActivatedArrays && scale.size() == 3 * n)
  {
    pd->AddArray(AdoptVector<vtkFloatArray>(arrays::Scale, std::move(scale), 3));
  }

  for (const auto& extra : cloud.Extra)
  {
    vtkSmartPointer<vtkDataArray> a;
    a.TakeReference(NewArrayFromExtra(extra));
    pd->AddArray(a);
  }
  if (shared)
  {
    // (copied into arrays of their own: the shared cloud is the model's parameters only)
    std::vector<ExtraProperty>().swap(cloud.Extra);
  }

  vtkNew<vtkIntArray> degree;
  degree->SetName(arrays::SHDegree);
  degree->InsertNextValue(cloud.ShDegree);
  output->GetFieldData()->AddArray(degree);
}
}

//------------------------------------------------------------------------------
void GaussianCloudToPolyData(const GaussianCloud& cloud,
  vtkPolyData* output,
  const PolyDataOptions& options)
{
  FillPolyData(const_cast<GaussianCloud&>(cloud), output, options, nullptr);
}

//------------------------------------------------------------------------------
void GaussianCloudToPolyData(GaussianCloud&& cloud,
  vtkPolyData* output,
  const PolyDataOptions& options)
{
  auto shared = std::make_shared<GaussianCloud>(std::move(cloud));
  cloud = GaussianCloud();
  FillPolyData(*shared, output, options, shared);
}

namespace
{
//------------------------------------------------------------------------------
// The SH degree PolyDataToGaussianCloud gives @p input (its SH array's, else the SHDegree field
// data's, else 0); false with a message when the SH array's component count is no degree.
bool SceneShDegree(vtkPolyData* input, int& degree, std::string* error)
{
  degree = -1;
  if (auto* fd = vtkIntArray::SafeDownCast(input->GetFieldData()->GetArray(arrays::SHDegree)))
  {
    if (fd->GetNumberOfTuples() > 0)
    {
      degree = fd->GetValue(0);
    }
  }
  if (vtkDataArray* sh = input->GetPointData()->GetArray(arrays::SH))
  {
    const int k = sh->GetNumberOfComponents() / 3;
    const int inferred = static_cast<int>(std::lround(std::sqrt(static_cast<double>(k)))) - 1;
    if (sh->GetNumberOfComponents() % 3 != 0 || (inferred + 1) * (inferred + 1) != k ||
      inferred > 3)
    {
      if (error)
      {
        *error = "array 'SH' has " + std::to_string(sh->GetNumberOfComponents()) +
          " components; expected 3*(D+1)^2 for an SH degree D of 0 to 3";
      }
      return false;
    }
    degree = inferred;
  }
  degree = degree < 0 ? 0 : degree;
  return true;
}
}

//------------------------------------------------------------------------------
std::shared_ptr<const GaussianCloud> SharedGaussianCloud(vtkPolyData* input)
{
  auto* points = input && input->GetPoints()
    ? vtkFloatArray::SafeDownCast(input->GetPoints()->GetData())
    : nullptr;
  const std::size_t n = input ? static_cast<std::size_t>(input->GetNumberOfPoints()) : 0;
  if (!points || n == 0 || points->GetNumberOfComponents() != 3)
  {
    return nullptr;
  }
  auto cloud = detail::FindCloudOf(points->GetPointer(0));
  if (!cloud || cloud->Count != n || !cloud->Extra.empty())
  {
    return nullptr;
  }
  // Each parameter array present is the cloud's vector of the same size; each one absent is an
  // empty vector in the cloud (as PolyDataToGaussianCloud would leave it).
  vtkPointData* pd = input->GetPointData();
  auto same = [&](const char* name, const void* data, std::size_t size, int type) -> bool
  {
    vtkDataArray* a = name ? pd->GetArray(name) : points;
    if (!a)
    {
      return size == 0;
    }
    return a->GetDataType() == type && a->GetNumberOfTuples() == static_cast<vtkIdType>(n) &&
      static_cast<std::size_t>(a->GetNumberOfValues()) == size && size > 0 &&
      a->GetVoidPointer(0) == data;
  };
  int degree = 0;
  if (!same(nullptr, cloud->Positions.data(), cloud->Positions.size(), VTK_FLOAT) ||
    !same(arrays::LogScale, cloud->LogScales.data(), cloud->LogScales.size(), VTK_FLOAT) ||
    !same(arrays::Rotation, cloud->Rotations.data(), cloud->Rotations.size(), VTK_FLOAT) ||
    !same(
      arrays::OpacityLogit, cloud->OpacityLogits.data(), cloud->OpacityLogits.size(), VTK_FLOAT) ||
    !same(arrays::SH, cloud->SH.data(), cloud->SH.size(), VTK_FLOAT) ||
    !same(arrays::GaussianId, cloud->Ids.data(), cloud->Ids.size(), VTK_ID_TYPE) ||
    !SceneShDegree(input, degree, nullptr) || degree != cloud->ShDegree)
  {
    return nullptr;
  }
  return cloud;
}

//------------------------------------------------------------------------------
std::shared_ptr<const GaussianCloud> GaussianCloudOf(vtkPolyData* input, std::string* error)
{
  if (auto shared = SharedGaussianCloud(input))
  {
    return shared;
  }
  auto cloud = std::make_shared<GaussianCloud>();
  if (!PolyDataToGaussianCloud(input, *cloud, error))
  {
    return nullptr;
  }
  return cloud;
}

//------------------------------------------------------------------------------
bool PolyDataToGaussianCloud(vtkPolyData* input,
  GaussianCloud& cloud,
  std::string* error,
  bool withExtras)
{
  cloud = GaussianCloud();
  if (!input || !input->GetPoints())
  {
    if (error)
    {
      *error = "the Gaussian scene has no points";
    }
    return false;
  }
  const std::size_t n = static_cast<std::size_t>(input->GetNumberOfPoints());
  cloud.Count = n;
  cloud.Positions.resize(3 * n);
  if (auto* f = vtkFloatArray::SafeDownCast(input->GetPoints()->GetData()))
  {
    if (n)
    {
      std::memcpy(cloud.Positions.data(), f->GetPointer(0), 3 * n * sizeof(float));
    }
  }
  else
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      double p[3];
      input->GetPoint(static_cast<vtkIdType>(i), p);
      for (int c = 0; c < 3; ++c)
      {
        cloud.Positions[3 * i + c] = static_cast<float>(p[c]);
      }
    }
  }

  vtkPointData* pd = input->GetPointData();
  if (!FetchFloats(pd, arrays::LogScale, 3, n, cloud.LogScales, error) ||
    !FetchFloats(pd, arrays::Rotation, 4, n, cloud.Rotations, error) ||
    !FetchFloats(pd, arrays::OpacityLogit, 1, n, cloud.OpacityLogits, error) ||
    !FetchFloats(pd, arrays::SH, 0, n, cloud.SH, error))
  {
    return false;
  }

  if (!SceneShDegree(input, cloud.ShDegree, error))
  {
    return false;
  }

  if (vtkDataArray* ids = pd->GetArray(arrays::GaussianId))
  {
    cloud.Ids.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      cloud.Ids[i] = static_cast<std::int64_t>(ids->GetTuple1(static_cast<vtkIdType>(i)));
    }
  }

  if (withExtras)
  {
    cloud.Extra = PolyDataExtraProperties(input);
  }
  return true;
}

//------------------------------------------------------------------------------
std::vector<ExtraProperty> PolyDataExtraProperties(vtkPolyData* input)
{
  std::vector<ExtraProperty> extras;
  vtkPointData* pd = input ? input->GetPointData() : nullptr;
  const std::size_t n = input ? static_cast<std::size_t>(input->GetNumberOfPoints()) : 0;
  if (!pd)
  {
    return extras;
  }
  static const std::set<std::string> model = { arrays::GaussianId,
    arrays::LogScale,
    arrays::Rotation,
    arrays::OpacityLogit,
    arrays::SH,
    arrays::Opacity,
    arrays::Scale };
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pd->GetArray(a);
    ScalarType type;
    if (!array || !array->GetName() || model.count(array->GetName()) ||
      !ScalarTypeFromVTK(array->GetDataType(), type))
    {
      continue;
    }
    const int components = array->GetNumberOfComponents();
    const std::size_t size = ScalarTypeSize(type);
    for (int c = 0; c < components; ++c)
    {
      ExtraProperty extra;
      extra.Name = components == 1 ? std::string(array->GetName())
                                   : std::string(array->GetName()) + "_" + std::to_string(c);
      extra.Type = type;
      extra.Bytes.resize(n * size);
      const auto* src = static_cast<const unsigned char*>(array->GetVoidPointer(0));
      for (std::size_t i = 0; i < n; ++i)
      {
        std::memcpy(extra.Bytes.data() + i * size, src + (i * components + c) * size, size);
      }
      extras.push_back(std::move(extra));
    }
  }
  return extras;
}

//------------------------------------------------------------------------------
void CamerasToTable(const std::vector<Camera>& cameras, vtkTable* table)
{
  table->Initialize();
  const vtkIdType n = static_cast<vtkIdType>(cameras.size());
  vtkNew<vtkStringArray> name, image, model;
  name->SetName(arrays::CameraName);
  image->SetName(arrays::CameraImage);
  model->SetName(arrays::CameraModel);
  vtkNew<vtkUnsignedCharArray> split;
  split->SetName(arrays::CameraSplit);
  vtkNew<vtkIntArray> width, height;
  width->SetName(arrays::CameraWidth);
  height->SetName(arrays::CameraHeight);
  vtkNew<vtkDoubleArray> fx, fy, cx, cy, w2c, distortion;
  fx->SetName(arrays::CameraFx);
  fy->SetName(arrays::CameraFy);
  cx->SetName(arrays::CameraCx);
  cy->SetName(arrays::CameraCy);
  w2c->SetName(arrays::CameraWorldToCamera);
  w2c->SetNumberOfComponents(16);
  distortion->SetName(arrays::CameraDistortion);
  distortion->SetNumberOfComponents(MaxDistortion);
  for (auto* a : std::initializer_list<vtkAbstractArray*>{
         name, image, model, split, width, height, fx, fy, cx, cy, w2c, distortion })
  {
    a->SetNumberOfTuples(n);
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    const Camera& c = cameras[static_cast<std::size_t>(i)];
    name->SetValue(i, c.Name);
    image->SetValue(i, c.ImagePath);
    model->SetValue(i, c.Model);
    split->SetValue(i, static_cast<unsigned char>(c.Split));
    width->SetValue(i, c.Width);
    height->SetValue(i, c.Height);
    fx->SetValue(i, c.Fx);
    fy->SetValue(i, c.Fy);
    cx->SetValue(i, c.Cx);
    cy->SetValue(i, c.Cy);
    w2c->SetTypedTuple(i, c.WorldToCamera.data());
    for (int k = 0; k < MaxDistortion; ++k)
    {
      distortion->SetTypedComponent(i,
        k,
        k < static_cast<int>(c.Distortion.size()) ? c.Distortion[static_cast<std::size_t>(k)]
                                                  : std::numeric_limits<double>::quiet_NaN());
    }
  }
  for (auto* a : std::initializer_list<vtkAbstractArray*>{
         name, split, width, height, fx, fy, cx, cy, w2c, image, model, distortion })
  {
    table->AddColumn(a);
  }
}

//------------------------------------------------------------------------------
vtkIdType FirstTrainingCamera(vtkTable* table)
{
  if (!table || table->GetNumberOfRows() == 0)
  {
    return -1;
  }
  auto* split = vtkDataArray::SafeDownCast(table->GetColumnByName(arrays::CameraSplit));
  for (vtkIdType r = 0; split && r < table->GetNumberOfRows(); ++r)
  {
    if (split->GetTuple1(r) == 0)
    {
      return r;
    }
  }
  return 0;
}

//------------------------------------------------------------------------------
bool TableToCameras(vtkTable* table, std::vector<Camera>& cameras, std::string* error)
{
  cameras.clear();
  auto column = [&](const char* colName) -> vtkAbstractArray*
  {
    vtkAbstractArray* a = table ? table->GetColumnByName(colName) : nullptr;
    if (!a && error)
    {
      *error = std::string("the camera table has no column '") + colName + "'";
    }
    return a;
  };
  auto* name = vtkStringArray::SafeDownCast(column(arrays::CameraName));
  auto* width = vtkDataArray::SafeDownCast(column(arrays::CameraWidth));
  auto* height = vtkDataArray::SafeDownCast(column(arrays::CameraHeight));
  auto* fx = vtkDataArray::SafeDownCast(column(arrays::CameraFx));
  auto* fy = vtkDataArray::SafeDownCast(column(arrays::CameraFy));
  auto* w2c = vtkDataArray::SafeDownCast(column(arrays::CameraWorldToCamera));
  if (!name || !width || !height || !fx || !fy || !w2c)
  {
    return false;
  }
  if (w2c->GetNumberOfComponents() != 16)
  {
    if (error)
    {
      *error = "the camera table's WorldToCamera column must have 16 components";
    }
    return false;
  }
  auto* split = vtkDataArray::SafeDownCast(table->GetColumnByName(arrays::CameraSplit));
  auto* cx = vtkDataArray::SafeDownCast(table->GetColumnByName(arrays::CameraCx));
  auto* cy = vtkDataArray::SafeDownCast(table->GetColumnByName(arrays::CameraCy));
  auto* image = vtkStringArray::SafeDownCast(table->GetColumnByName(arrays::CameraImage));
  auto* model = vtkStringArray::SafeDownCast(table->GetColumnByName(arrays::CameraModel));
  auto* distortion = vtkDataArray::SafeDownCast(table->GetColumnByName(arrays::CameraDistortion));
  const vtkIdType n = table->GetNumberOfRows();
  cameras.resize(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    Camera& c = cameras[static_cast<std::size_t>(i)];
    c.Name = name->GetValue(i);
    c.Split = split && split->GetTuple1(i) != 0 ? CameraSplit::Test : CameraSplit::Train;
    c.Width = static_cast<int>(width->GetTuple1(i));
    c.Height = static_cast<int>(height->GetTuple1(i));
    c.Fx = fx->GetTuple1(i);
    c.Fy = fy->GetTuple1(i);
    c.Cx = cx ? cx->GetTuple1(i) : c.Width / 2.0;
    c.Cy = cy ? cy->GetTuple1(i) : c.Height / 2.0;
    w2c->GetTuple(i, c.WorldToCamera.data());
    c.ImagePath = image ? image->GetValue(i) : std::string();
    c.Model = model ? model->GetValue(i) : std::string();
    if (distortion)
    {
      for (int k = 0; k < distortion->GetNumberOfComponents(); ++k)
      {
        const double v = distortion->GetComponent(i, k);
        if (std::isnan(v))
        {
          break;
        }
        c.Distortion.push_back(v);
      }
    }
  }
  return true;
}

} // namespace vis4gs
