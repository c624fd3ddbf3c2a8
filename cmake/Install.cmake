# `cmake --install`: the libraries a host links (s3d::vkcore, s3d::stereo, s3d::renderer, s3d::frame, s3d::comfort, s3d::hud,
# s3d::io for image and depth files, s3d::capi for C hosts),
# their public headers (shaders stay embedded in the libraries), an exported CMake package with a version file,
# and a pkg-config file. A consumer: find_package(s3d 0.4 CONFIG REQUIRED) + target_link_libraries(app s3d::stereo).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(S3D_PACKAGE_LIBRARIES vkcore stereo renderer frame comfort hud io capi)
set(S3D_PACKAGE_TARGETS "")
foreach(name ${S3D_PACKAGE_LIBRARIES})
  set_target_properties(s3d_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(s3d_${name} INTERFACE $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  list(APPEND S3D_PACKAGE_TARGETS s3d_${name})
endforeach()

install(TARGETS ${S3D_PACKAGE_TARGETS} EXPORT s3dTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(dir vk/include stereo/include renderer/include frame/include comfort/include hud/include io/include capi/include)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()

set(S3D_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/s3d)
install(EXPORT s3dTargets NAMESPACE s3d:: DESTINATION ${S3D_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/s3dConfig.cmake.in ${PROJECT_BINARY_DIR}/s3dConfig.cmake
                              INSTALL_DESTINATION ${S3D_CMAKE_DIR})
# 0.x: a new minor version may change the API, so only the same minor version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/s3dConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/s3dConfig.cmake ${PROJECT_BINARY_DIR}/s3dConfigVersion.cmake DESTINATION ${S3D_CMAKE_DIR})

# s3d.pc finds the prefix from its own folder (${pcfiledir}), so `cmake --install --prefix DIR` into any folder, and
# moving that folder later, leaves it correct; an absolute CMAKE_INSTALL_LIBDIR pins it to the configured prefix.
set(S3D_PC_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(S3D_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH S3D_PC_UP "/prefix/${S3D_PC_DIR}" "/prefix")
  string(REGEX REPLACE "/$" "" S3D_PC_UP "${S3D_PC_UP}")  # lib/pkgconfig: ../..
  set(S3D_PC_PREFIX "\${pcfiledir}/${S3D_PC_UP}")
endif()
foreach(dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
    set(S3D_PC_${dir} "${CMAKE_INSTALL_${dir}}")
  else()
    set(S3D_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
  endif()
endforeach()
configure_file(${PROJECT_SOURCE_DIR}/cmake/s3d.pc.in ${PROJECT_BINARY_DIR}/s3d.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/s3d.pc DESTINATION ${S3D_PC_DIR})
