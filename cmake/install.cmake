# voxcast as a CMake package (issue 22): `cmake --install build/release
# --prefix P` puts the libraries, their headers and the `voxcast` command in P;
# another project then writes
#
#   find_package(voxcast CONFIG REQUIRED)
#   target_link_libraries(my_testbench PRIVATE voxcast::hls voxcast::refmodel)
#
# and gets the targets with their usage requirements:
#   voxcast::refmodel  the double-precision reference, the bit-true model, scenes, volumes
#   voxcast::hls       the synthesizable kernels (header-only; on voxcast::refmodel)
#   voxcast::rtl       the cycle model of the card
#   voxcast::cosim     the harness (engines side by side, reports)
#   voxcast::voxcast   the command
# The build's warning policy stays in this project; what the results depend on
# (-ffp-contract=off: voxcast::fp_contract) travels with the targets. The test
# package.consumer builds a project against an installed tree (tests/package/).
include(CMakePackageConfigHelpers)

set(VOXCAST_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/voxcast)

set_target_properties(voxcast_refmodel PROPERTIES EXPORT_NAME refmodel)
set_target_properties(voxcast_hls PROPERTIES EXPORT_NAME hls)
set_target_properties(voxcast_rtl PROPERTIES EXPORT_NAME rtl)
set_target_properties(voxcast_cosim PROPERTIES EXPORT_NAME cosim)

install(TARGETS voxcast_refmodel voxcast_hls voxcast_rtl voxcast_cosim voxcast_fp voxcast_nifti
                voxcast
        EXPORT voxcastTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The image module voxcast loads on its first image (cosim/reports/image_io_module.hpp):
# found from the installed command as bin/../LIBDIR/voxcast.
install(TARGETS voxcast_image_io LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/voxcast)

# Headers keep their paths below include/voxcast, so `#include "hls/..."`
# reads the same in the tree and in a consumer.
foreach(layer refmodel hls rtl_model cosim)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${layer}
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/voxcast
          FILES_MATCHING PATTERN "*.hpp"
          PATTERN "tb" EXCLUDE)
endforeach()

install(EXPORT voxcastTargets
        NAMESPACE voxcast::
        DESTINATION ${VOXCAST_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/voxcastConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/voxcastConfig.cmake
                              INSTALL_DESTINATION ${VOXCAST_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/voxcastConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/voxcastConfig.cmake
              ${PROJECT_BINARY_DIR}/voxcastConfigVersion.cmake
        DESTINATION ${VOXCAST_INSTALL_CMAKEDIR})
