// SPDX-License-Identifier: BSD-3-Clause
// Reading a .vtu file back in a test (VTK's XML reader).
#pragma once

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

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

}  // namespace igac_test
