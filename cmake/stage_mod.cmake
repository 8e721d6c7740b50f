# Mirrors the workbench sources and resources into the staged Mod folder, removing
# files that are gone from the source tree; keeps the compiled _core module and the
# hapticad-bench-mesh program.
# Usage: cmake -DSTAGE=... -DPLUGIN=... -DRESOURCES=... -P stage_mod.cmake
file(GLOB_RECURSE staged LIST_DIRECTORIES false "${STAGE}/*")
foreach(f IN LISTS staged)
  if(NOT f MATCHES "/hapticad/(_core[^/]*\\.so|hapticad-bench-mesh)$")
    file(REMOVE "${f}")
  endif()
endforeach()
file(COPY "${PLUGIN}/" DESTINATION "${STAGE}" PATTERN "__pycache__" EXCLUDE)
file(COPY "${RESOURCES}/" DESTINATION "${STAGE}/resources" PATTERN "*.FCStd1" EXCLUDE)  # FreeCAD's backups
# drop folders left empty by removed sources
file(GLOB_RECURSE dirs LIST_DIRECTORIES true "${STAGE}/*")
list(REVERSE dirs)
foreach(d IN LISTS dirs)
  if(IS_DIRECTORY "${d}")
    file(GLOB content "${d}/*")
    if(NOT content)
      file(REMOVE_RECURSE "${d}")
    endif()
  endif()
endforeach()
