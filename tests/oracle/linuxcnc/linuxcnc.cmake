# The LinuxCNC kinematics oracle (tests/oracle/linuxcnc/kins_oracle.sh, docs/kinematics.md
# "What is verified"): `twinpost kin` against the joints LinuxCNC's own kinematics modules
# command, one ctest entry per chain:
#   oracle.linuxcnc-kins.trt      xyzac-trt-kins, the A/C trunnion of trt.toml
#   oracle.linuxcnc-kins.bridge   5axiskins, the C/B head bridge mill of bridge.toml
# Optional: skipped (exit 77), not failed, where LinuxCNC is not installed. Nothing in the
# build depends on it. Included from the top CMakeLists.txt inside its tests section.
find_program(TWINPOST_BASH bash)
if(TWINPOST_BASH)
  foreach(_tp_chain trt bridge)
    add_test(NAME oracle.linuxcnc-kins.${_tp_chain}
             COMMAND ${TWINPOST_BASH} ${CMAKE_CURRENT_LIST_DIR}/kins_oracle.sh $<TARGET_FILE:twinpost>
                     ${CMAKE_SOURCE_DIR} ${_tp_chain} ${CMAKE_BINARY_DIR}/oracle-linuxcnc/${_tp_chain})
    set_tests_properties(oracle.linuxcnc-kins.${_tp_chain} PROPERTIES
                         LABELS "oracle" SKIP_RETURN_CODE 77 TIMEOUT 120 RESOURCE_LOCK linuxcnc)
  endforeach()
endif()
