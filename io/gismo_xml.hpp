// SPDX-License-Identifier: BSD-3-Clause
// NURBS geometry files in the XML format of G+Smo (gismo/gismo,
// src/gsIO/gsXml*.{h,hpp,cpp}; example files in its filedata/ folder), the
// format isogeometric codes use to exchange multi-patch NURBS models.
//
//   <xml>
//    <Geometry type="TensorNurbs2" id="0">          (or TensorBSpline2, ...3)
//     <Basis type="TensorNurbsBasis2">               (TensorBSpline: no wrapper)
//      <Basis type="TensorBSplineBasis2">
//       <Basis type="BSplineBasis" index="0">
//        <KnotVector degree="2">0 0 0 1 1 1</KnotVector>
//       </Basis> ... one per parametric direction
//      </Basis>
//      <weights>1 0.7071 1 ...</weights>             (one per control point)
//     </Basis>
//     <coefs geoDim="2">0 -1                         (control points, one row
//      1 -1 ...</coefs>                               each, u fastest)
//    </Geometry> ...
//    <MultiPatch parDim="2" id="2">
//     <patches type="id_range">0 1</patches>         (or id_index: a list of ids)
//     <interfaces>0 2 1 1 0 1 1 1</interfaces>       (patch side patch side, then
//                                                     the direction map and the
//                                                     orientation flags, d each)
//     <boundary>0 1 0 3 ...</boundary>               (patch side pairs)
//    </MultiPatch>
//   </xml>
//
// Patch numbers in <interfaces> and <boundary> are the ids of the Geometry
// elements (G+Smo maps them through the <patches> list, gsXml.cpp
// getInterfaces); igac renumbers the patches 0, 1, ... in the order of
// <patches>.  Sides: 1 west u = 0, 2 east u = 1, 3 south v = 0, 4 north v = 1,
// 5 front w = 0, 6 back w = 1 (engine/geometry/multipatch.hpp).  A file with
// a single <Geometry> and no <MultiPatch> is a one-patch body.
//
// igac reads solid bodies: the geometric dimension equals the parametric one
// (2 or 3).  Every defect is an InputError with one line
// "FILE:LINE: <element>: reason".
#pragma once

#include <string>

#include "engine/geometry/multipatch.hpp"

namespace igac {

// Throws InputError.
MultiPatch read_gismo_xml(const std::string& path);

// Writes every number with 17 significant digits (reading it back gives the
// same doubles), under a temporary name renamed at the end.  Interfaces get
// the direction map and orientation that G+Smo expects, found from the
// sides' corner control points.  Throws InputError when the body cannot be
// described (no patches, mixed dimensions, interface sides that do not meet)
// or the file cannot be written.
void write_gismo_xml(const MultiPatch& body, const std::string& path);


}  // namespace igac
