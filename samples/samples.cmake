# Golden tests through the real command line (docs/samples.md).
#
#   sample.<job>.<machine>   samples/<job>/job.cls posted for a built-in machine; stdout,
#                            stderr and every written file must equal samples/<job>/expected/
#   sample.check.<case>      `twinpost check` on hand-made NC programs in samples/check/<case>/
#   sample.timeline.<case>   `twinpost timeline` on hand-made NC programs in samples/timeline/<case>/
#   sample.post-fail.<case>  a post that must fail, with its exact message, writing nothing
#   oracle.<job>.<machine>   tests/oracle/rs274_endpoints.sh: the posted motion read back by
#                            LinuxCNC's rs274 against the CL end points (skipped, exit 77,
#                            where rs274 or python3 is missing)
#
# Included from the top CMakeLists.txt inside its tests section; needs the `twinpost` target.

set(TWINPOST_SAMPLES_DIR ${CMAKE_CURRENT_LIST_DIR})
set(TWINPOST_SAMPLE_RUNNER ${TWINPOST_SAMPLES_DIR}/run_sample.cmake)
set(TWINPOST_SAMPLE_WORK ${CMAKE_BINARY_DIR}/sample-runs)

# Posts whose current output is known to be wrong. Their tests are registered but disabled
# (ctest lists them as "Not Run (Disabled)") and they have no golden files, so that a wrong
# program is never frozen as the expected one. Remove an entry once the bug is fixed, then
# make and review its golden files (docs/samples.md). None at present.
set(TWINPOST_SAMPLE_KNOWN_BAD)

file(GLOB _tp_machine_files CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/machines/builtin/*.toml)
set(_tp_machines "")
foreach(_tp_file IN LISTS _tp_machine_files)
  get_filename_component(_tp_name ${_tp_file} NAME_WE)
  list(APPEND _tp_machines ${_tp_name})
endforeach()
list(SORT _tp_machines)
# Machines for `twinpost check` only: post refuses them (citizen-2system writes !2L1, which
# the post does not write yet; star-3path is machine.check_only), so the jobs are not posted
# for them; their samples are the checker's (samples/check/citizen-*, star-*).
list(REMOVE_ITEM _tp_machines citizen-2system star-3path)
# The milling machines with a kinematic chain: the turning jobs are not posted for them. A
# job that is posted only on some machines names them in its `machines` file (one per line),
# e.g. the multi-axis jobs on the 5-axis and 4-axis mills; the rs274 oracle, which reads the
# words as tool-tip positions, does not run on them (their X Y Z are joints or need G43.4).
set(TWINPOST_MULTIAXIS_MACHINES head-head-5axis rotary-4axis trunnion-5axis)
list(REMOVE_ITEM _tp_machines ${TWINPOST_MULTIAXIS_MACHINES})

find_program(TWINPOST_BASH bash)
set(_tp_oracle ${CMAKE_SOURCE_DIR}/tests/oracle/rs274_endpoints.sh)

file(GLOB _tp_jobs CONFIGURE_DEPENDS ${TWINPOST_SAMPLES_DIR}/*/job.cls)
foreach(_tp_job IN LISTS _tp_jobs)
  get_filename_component(_tp_dir ${_tp_job} DIRECTORY)
  get_filename_component(_tp_sample ${_tp_dir} NAME)
  # Extra post options of a sample (e.g. --sync auto) live in its post.args.
  set(_tp_args "")
  if(EXISTS ${_tp_dir}/post.args)
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_tp_dir}/post.args)
    file(READ ${_tp_dir}/post.args _tp_text)
    string(STRIP "${_tp_text}" _tp_text)
    string(REPLACE "\n" " " _tp_text "${_tp_text}")
    separate_arguments(_tp_args UNIX_COMMAND "${_tp_text}")
  endif()
  # A job for some machines only (mill/turn, 5-axis) names them in its `machines` file;
  # the others post on every built-in post machine.
  set(_tp_job_machines ${_tp_machines})
  if(EXISTS ${_tp_dir}/machines)
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_tp_dir}/machines)
    file(STRINGS ${_tp_dir}/machines _tp_job_machines REGEX "^[^#]")
  endif()
  foreach(_tp_machine IN LISTS _tp_job_machines)
    set(_tp_id ${_tp_sample}.${_tp_machine})
    add_test(NAME sample.${_tp_id}
             COMMAND ${CMAKE_COMMAND} -DTWINPOST=$<TARGET_FILE:twinpost> -DMODE=post
                     -DCASE_DIR=${_tp_dir} -DMACHINE=${_tp_machine}
                     -DWORK_DIR=${TWINPOST_SAMPLE_WORK}/${_tp_id}
                     -P ${TWINPOST_SAMPLE_RUNNER})
    set_tests_properties(sample.${_tp_id} PROPERTIES LABELS "sample")
    # No oracle on the multi-axis mills (joints, G43.4) unless the job's `rotaries-at-zero` file
    # says its rotary axes never leave 0 (X Y Z are then the tip), nor for a job whose `no-oracle`
    # file says why rs274 cannot read its programs (polar interpolation, C, a turned frame).
    if(TWINPOST_BASH AND EXISTS ${_tp_oracle}
       AND (NOT _tp_machine IN_LIST TWINPOST_MULTIAXIS_MACHINES OR EXISTS ${_tp_dir}/rotaries-at-zero)
       AND NOT EXISTS ${_tp_dir}/no-oracle)
      add_test(NAME oracle.${_tp_id}
               COMMAND ${TWINPOST_BASH} ${_tp_oracle} $<TARGET_FILE:twinpost> ${_tp_job} ${_tp_machine}
                       ${TWINPOST_SAMPLE_WORK}/oracle.${_tp_id} ${_tp_args})
      set_tests_properties(oracle.${_tp_id} PROPERTIES LABELS "oracle" SKIP_RETURN_CODE 77)
    endif()
    if(_tp_id IN_LIST TWINPOST_SAMPLE_KNOWN_BAD)
      set_tests_properties(sample.${_tp_id} PROPERTIES DISABLED TRUE)
      if(TEST oracle.${_tp_id})
        set_tests_properties(oracle.${_tp_id} PROPERTIES DISABLED TRUE)
      endif()
    endif()
  endforeach()
endforeach()

# Hand-made NC programs for the checker, and posts that must fail: each case folder holds
# its inputs, `args` (the command line after `check`, or after `post job.cls -o out`) and
# expected.stdout / expected.stderr / expected.rc.
foreach(_tp_mode check timeline post-fail)
  file(GLOB _tp_cases CONFIGURE_DEPENDS ${TWINPOST_SAMPLES_DIR}/${_tp_mode}/*/args)
  foreach(_tp_case_args IN LISTS _tp_cases)
    get_filename_component(_tp_dir ${_tp_case_args} DIRECTORY)
    get_filename_component(_tp_case ${_tp_dir} NAME)
    add_test(NAME sample.${_tp_mode}.${_tp_case}
             COMMAND ${CMAKE_COMMAND} -DTWINPOST=$<TARGET_FILE:twinpost> -DMODE=${_tp_mode}
                     -DCASE_DIR=${_tp_dir} -DWORK_DIR=${TWINPOST_SAMPLE_WORK}/${_tp_mode}.${_tp_case}
                     -P ${TWINPOST_SAMPLE_RUNNER})
    set_tests_properties(sample.${_tp_mode}.${_tp_case} PROPERTIES LABELS "sample")
  endforeach()
endforeach()
