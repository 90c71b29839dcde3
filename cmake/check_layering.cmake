# SPDX-License-Identifier: BSD-3-Clause
# Fails the build when a source file includes a header of a folder above its
# own: materials/ < engine/ < contact/ < solvers/ < model/ < io/ < app/ < python/
# (docs/design.md, "Layout").
# Run by the check_layering target on every build.
cmake_policy(SET CMP0057 NEW)  # if(... IN_LIST ...), in script mode too
set(levels materials engine contact solvers model io app python)
list(LENGTH levels n_levels)
math(EXPR last "${n_levels} - 1")
set(bad "")
foreach(i RANGE 0 ${last})
  list(GET levels ${i} folder)
  math(EXPR above_first "${i} + 1")
  if(above_first GREATER ${last})
    continue()
  endif()
  file(GLOB_RECURSE sources "${SOURCE_DIR}/${folder}/*.cpp" "${SOURCE_DIR}/${folder}/*.hpp")
  foreach(src IN LISTS sources)
    file(STRINGS "${src}" includes REGEX "^#include \"[a-z_]+/")
    foreach(line IN LISTS includes)
      foreach(j RANGE ${above_first} ${last})
        list(GET levels ${j} upper)
        if(line MATCHES "^#include \"${upper}/")
          file(RELATIVE_PATH rel "${SOURCE_DIR}" "${src}")
          string(APPEND bad "\n  ${rel}: ${line} (${folder}/ must not depend on ${upper}/)")
        endif()
      endforeach()
    endforeach()
  endforeach()
endforeach()
# app/ (the command line) and io/ (file formats) compute nothing: of the
# folders below model/ they include only the headers allowed here (data
# types, registries of names, error types), never a numerical kernel: such
# work belongs to model/, which they include freely.  An allow-list, so that
# a new kernel header is kept out without anyone listing it; adding a header
# here is a decision about what it is, with its reason.
set(allowed
    engine/stopwatch                  # the console's times
    engine/spline/knot_vector         # SplineError, caught and reported as an input error
    engine/spline/bezier_extraction   # ParaView's rational Bezier cells are the extraction operators
    engine/geometry/shapes            # the built-in shapes' names and keys (case files)
    engine/geometry/multipatch        # a multi-patch geometry (G+Smo XML files)
    engine/load_curve                 # LoadCurve, a case's curves, and how many load steps they make (case files)
    contact/obstacle                  # the obstacle types' names and keys (case files)
    contact/interface_law             # the interface laws' names and whether they take a coefficient (case files)
    contact/friction_state            # open / stick / slip and the slip history (outputs, state files)
    materials/hyperelastic            # the material laws' names and keys (case files)
    solvers/petsc_contact)            # PetscSession: MPI and PETSc started and ended by the program
foreach(folder app io)
  file(GLOB_RECURSE sources "${SOURCE_DIR}/${folder}/*.cpp" "${SOURCE_DIR}/${folder}/*.hpp")
  foreach(src IN LISTS sources)
    file(STRINGS "${src}" includes REGEX "^#include \"(materials|engine|contact|solvers)/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include \"([^\"]+)\\.hpp\".*" "\\1" header "${line}")
      if(NOT header IN_LIST allowed)
        file(RELATIVE_PATH rel "${SOURCE_DIR}" "${src}")
        string(APPEND bad "\n  ${rel}: ${line} (${folder}/ computes nothing: only the headers check_layering.cmake "
                          "allows, a numerical kernel belongs to model/)")
      endif()
    endforeach()
  endforeach()
endforeach()
# Every source file names its licence (LICENSE) on its first line.
foreach(folder IN LISTS levels ITEMS tests bench)
  file(GLOB_RECURSE sources "${SOURCE_DIR}/${folder}/*.cpp" "${SOURCE_DIR}/${folder}/*.hpp")
  foreach(src IN LISTS sources)
    file(STRINGS "${src}" first LIMIT_COUNT 1)
    if(NOT first STREQUAL "// SPDX-License-Identifier: BSD-3-Clause")
      file(RELATIVE_PATH rel "${SOURCE_DIR}" "${src}")
      string(APPEND bad "\n  ${rel}: the first line is not // SPDX-License-Identifier: BSD-3-Clause")
    endif()
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "igac: layering broken:${bad}")
endif()
