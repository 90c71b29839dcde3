// SPDX-License-Identifier: BSD-3-Clause
// Reading a .vtu file back in a test (VTK's XML reader).
#pragma once

#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <string>

namespace igac_test {

inline vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::string& path) {
  vtkNew<vtkXMLUnstructuredGridReader> r;
  r->SetFileName(path.c_str());
  r->Update();
  auto g = vtkSmartPointer<vtkUnstructuredGrid>::New();
  g->ShallowCopy(r->GetOutput());
  return g;
}

// The smallest value of the point array `array` (its first component) over
// every body file (solution_XXXX.vtu) of the output folder `out`; `files`
// receives how many there are (+inf and 0 when none).
inline double min_over_steps(const std::filesystem::path& out, const char* array, int& files) {
  double lo = std::numeric_limits<double>::infinity();
  files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("solution_", 0) != 0 || entry.path().extension() != ".vtu") continue;
    ++files;
    const auto g = read_vtu(entry.path().string());
    vtkDataArray* a = g->GetPointData()->GetArray(array);
    EXPECT_NE(a, nullptr) << name << ": no " << array;
    if (!a) continue;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) lo = std::min(lo, a->GetComponent(i, 0));
  }
  return lo;
}

}  // namespace igac_test
