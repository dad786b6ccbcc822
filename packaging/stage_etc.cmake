# Run by cpack after it installs into its staging folder: the filter's configuration as shipped
# (share/hkf/hkf-filter.conf) also becomes the system's, /etc/hkf/hkf-filter.conf, a conffile
# (debian/conffiles): an administrator's changes survive upgrades.
file(GLOB staged LIST_DIRECTORIES true "${CPACK_TEMPORARY_DIRECTORY}/*")
set(shipped "${CPACK_TEMPORARY_DIRECTORY}/usr/share/hkf/hkf-filter.conf")
if(NOT EXISTS "${shipped}")
  message(FATAL_ERROR "stage_etc.cmake: no ${shipped} in the staging folder (${staged})")
endif()
file(MAKE_DIRECTORY "${CPACK_TEMPORARY_DIRECTORY}/etc/hkf")
file(COPY_FILE "${shipped}" "${CPACK_TEMPORARY_DIRECTORY}/etc/hkf/hkf-filter.conf")
