# Golden test runner: runs the real twinpost binary in a fresh folder and compares what it
# prints and writes, byte for byte, with the expected files kept beside the case.
#
#   cmake -DTWINPOST=<binary> -DMODE=<mode> -DCASE_DIR=<dir> -DWORK_DIR=<fresh dir>
#         [-DMACHINE=<name>] -P run_sample.cmake
#
# Modes:
#   post       CASE_DIR/job.cls is posted:  twinpost post job.cls --machine MACHINE -o out
#              [+ the words of CASE_DIR/post.args]. Expected: exit code 0, stdout equal to
#              expected/MACHINE.stdout, stderr equal to expected/MACHINE.stderr (empty when
#              that file is missing), and out/ holding exactly the files of expected/MACHINE/.
#   check      twinpost check <the words of CASE_DIR/args>, run beside copies of the case's
#              NC files. Expected: expected.stdout, expected.stderr (or empty), expected.rc.
#   timeline   twinpost timeline <the words of CASE_DIR/args>, as check (its summary or --json).
#   post-fail  twinpost post job.cls -o out <the words of CASE_DIR/args>. Expected:
#              expected.stdout, expected.stderr (or empty), expected.rc, and no file written.
#
# The job and NC files are copied into WORK_DIR and named relatively, so that messages and
# the "wrote" lines do not depend on where the source or build tree lives.
#
# After a deliberate change of the output, set TWINPOST_UPDATE_GOLDEN=1 in the environment:
# the runner then writes what twinpost produced into the expected files instead of
# comparing (review the result with `git diff samples/` before committing it).
cmake_minimum_required(VERSION 3.20)

foreach(var TWINPOST MODE CASE_DIR WORK_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_sample.cmake: -D${var}=... is required")
  endif()
endforeach()
foreach(var TWINPOST CASE_DIR WORK_DIR)
  get_filename_component(${var} "${${var}}" ABSOLUTE)
endforeach()
if(NOT EXISTS "${TWINPOST}")
  message(FATAL_ERROR "run_sample.cmake: twinpost binary '${TWINPOST}' does not exist")
endif()

set(update OFF)
if("$ENV{TWINPOST_UPDATE_GOLDEN}" STREQUAL "1")
  set(update ON)
endif()

set(failures "")
macro(fail text)
  string(APPEND failures "${text}\n")
endmacro()

# Words of an args file (shell-like quoting); empty when the file is missing.
function(read_args file out)
  set(words "")
  if(EXISTS "${file}")
    file(READ "${file}" text)
    string(STRIP "${text}" text)
    string(REPLACE "\n" " " text "${text}")
    separate_arguments(words UNIX_COMMAND "${text}")
  endif()
  set(${out} "${words}" PARENT_SCOPE)
endfunction()

# Splits a file into a list of lines; ';', '[' and ']' are kept out of the list syntax.
function(read_lines file out)
  set(lines "")
  if(EXISTS "${file}")
    file(READ "${file}" text)
    string(REPLACE ";" "<semicolon>" text "${text}")
    string(REPLACE "[" "<lb>" text "${text}")
    string(REPLACE "]" "<rb>" text "${text}")
    string(REPLACE "\r" "<CR>" text "${text}")
    string(REPLACE "\n" ";" text "${text}")
    set(lines "${text}")
  endif()
  set(${out} "${lines}" PARENT_SCOPE)
endfunction()

function(unescape_line in out)
  set(s "${in}")
  string(REPLACE "<semicolon>" ";" s "${s}")
  string(REPLACE "<lb>" "[" s "${s}")
  string(REPLACE "<rb>" "]" s "${s}")
  set(${out} "${s}" PARENT_SCOPE)
endfunction()

# A diff-like report: `diff -u` when the system has it, else the first differing lines.
function(describe_difference expected actual label out)
  find_program(DIFF_PROGRAM diff)
  if(DIFF_PROGRAM AND EXISTS "${expected}" AND EXISTS "${actual}")
    execute_process(COMMAND "${DIFF_PROGRAM}" -u --label "expected ${label}" --label "actual ${label}"
                            "${expected}" "${actual}"
                    OUTPUT_VARIABLE d ERROR_VARIABLE e)
    string(LENGTH "${d}" n)
    if(n GREATER 6000)
      string(SUBSTRING "${d}" 0 6000 d)
      string(APPEND d "\n[... diff cut at 6000 characters]\n")
    endif()
    set(${out} "${d}${e}" PARENT_SCOPE)
    return()
  endif()
  read_lines("${expected}" exp)
  read_lines("${actual}" act)
  list(LENGTH exp ne)
  list(LENGTH act na)
  set(n ${ne})
  if(na GREATER n)
    set(n ${na})
  endif()
  set(report "--- expected ${label}\n+++ actual ${label}\n")
  set(shown 0)
  set(i 0)
  while(i LESS n AND shown LESS 12)
    set(e "<no line>")
    set(a "<no line>")
    if(i LESS ne)
      list(GET exp ${i} e)
    endif()
    if(i LESS na)
      list(GET act ${i} a)
    endif()
    if(NOT e STREQUAL a)
      math(EXPR line "${i} + 1")
      unescape_line("${e}" e)
      unescape_line("${a}" a)
      string(APPEND report "line ${line}:\n-${e}\n+${a}\n")
      math(EXPR shown "${shown} + 1")
    endif()
    math(EXPR i "${i} + 1")
  endwhile()
  set(${out} "${report}" PARENT_SCOPE)
endfunction()

# Compares (or, when updating, stores) one produced text with its golden file.
# An absent golden stands for empty text when `empty_ok` is set.
function(check_text actual_file expected_file label empty_ok)
  if(update)
    file(READ "${actual_file}" text)
    if(text STREQUAL "" AND empty_ok)
      file(REMOVE "${expected_file}")
    else()
      get_filename_component(dir "${expected_file}" DIRECTORY)
      file(MAKE_DIRECTORY "${dir}")
      configure_file("${actual_file}" "${expected_file}" COPYONLY)
    endif()
    return()
  endif()
  set(golden "${expected_file}")
  if(NOT EXISTS "${golden}")
    if(NOT empty_ok)
      set(failures "${failures}${label}: no golden file ${expected_file}\n" PARENT_SCOPE)
      return()
    endif()
    set(golden "${WORK_DIR}/empty.txt")
    file(WRITE "${golden}" "")
  endif()
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${golden}" "${actual_file}" RESULT_VARIABLE same)
  if(NOT same EQUAL 0)
    describe_difference("${golden}" "${actual_file}" "${label}" d)
    set(failures "${failures}${label} differs from ${expected_file}:\n${d}\n" PARENT_SCOPE)
  endif()
endfunction()

# Relative paths of every file under `dir` (hidden ones included), sorted.
function(list_files dir out)
  set(files "")
  if(IS_DIRECTORY "${dir}")
    file(GLOB_RECURSE files LIST_DIRECTORIES false RELATIVE "${dir}" "${dir}/*" "${dir}/.*")
    list(REMOVE_DUPLICATES files)
    list(SORT files)
  endif()
  set(${out} "${files}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

if(MODE STREQUAL "post")
  if(NOT DEFINED MACHINE)
    message(FATAL_ERROR "run_sample.cmake: mode post needs -DMACHINE=...")
  endif()
  configure_file("${CASE_DIR}/job.cls" "${WORK_DIR}/job.cls" COPYONLY)
  # A machine file of the sample (its `machines` file names it as NAME.toml, read from here),
  # and the files beside it: its script, the files the script reads (docs/scripting.md).
  file(GLOB machine_files LIST_DIRECTORIES false RELATIVE "${CASE_DIR}" "${CASE_DIR}/*.toml"
       "${CASE_DIR}/*.lua" "${CASE_DIR}/*.csv")
  foreach(f IN LISTS machine_files)
    configure_file("${CASE_DIR}/${f}" "${WORK_DIR}/${f}" COPYONLY)
  endforeach()
  read_args("${CASE_DIR}/post.args" extra)
  set(command "${TWINPOST}" post job.cls --machine "${MACHINE}" -o out ${extra})
  set(expected_stdout "${CASE_DIR}/expected/${MACHINE}.stdout")
  set(expected_stderr "${CASE_DIR}/expected/${MACHINE}.stderr")
  set(expected_rc 0)
elseif(MODE STREQUAL "post-fail" OR MODE STREQUAL "check" OR MODE STREQUAL "timeline")
  file(GLOB inputs LIST_DIRECTORIES false RELATIVE "${CASE_DIR}" "${CASE_DIR}/*")
  foreach(f IN LISTS inputs)
    if(NOT f MATCHES "^(expected\\..*|args)$")
      configure_file("${CASE_DIR}/${f}" "${WORK_DIR}/${f}" COPYONLY)
    endif()
  endforeach()
  read_args("${CASE_DIR}/args" extra)
  if(MODE STREQUAL "check" OR MODE STREQUAL "timeline")
    set(command "${TWINPOST}" ${MODE} ${extra})
  else()
    set(command "${TWINPOST}" post job.cls -o out ${extra})
  endif()
  set(expected_stdout "${CASE_DIR}/expected.stdout")
  set(expected_stderr "${CASE_DIR}/expected.stderr")
  set(expected_rc "")
  if(EXISTS "${CASE_DIR}/expected.rc")
    file(READ "${CASE_DIR}/expected.rc" expected_rc)
    string(STRIP "${expected_rc}" expected_rc)
  elseif(NOT update)
    fail("no golden file ${CASE_DIR}/expected.rc")
  endif()
else()
  message(FATAL_ERROR "run_sample.cmake: unknown MODE '${MODE}' (post, check, timeline or post-fail)")
endif()

execute_process(COMMAND ${command}
                WORKING_DIRECTORY "${WORK_DIR}"
                RESULT_VARIABLE rc
                OUTPUT_FILE "${WORK_DIR}/actual.stdout"
                ERROR_FILE "${WORK_DIR}/actual.stderr")
string(REPLACE ";" " " shown_command "${command}")

if(update AND MODE STREQUAL "post" AND NOT rc EQUAL 0)
  file(READ "${WORK_DIR}/actual.stderr" err)
  message(FATAL_ERROR "not updating: '${shown_command}' exited with ${rc}\n${err}")
endif()
if(update AND NOT MODE STREQUAL "post")
  file(WRITE "${CASE_DIR}/expected.rc" "${rc}\n")
elseif(NOT "${rc}" STREQUAL "${expected_rc}")
  fail("exit code ${rc}, expected ${expected_rc}")
endif()
check_text("${WORK_DIR}/actual.stdout" "${expected_stdout}" "stdout" ON)
check_text("${WORK_DIR}/actual.stderr" "${expected_stderr}" "stderr" ON)

if(MODE STREQUAL "post")
  # Every expected file, byte for byte, and nothing else.
  set(expected_dir "${CASE_DIR}/expected/${MACHINE}")
  list_files("${WORK_DIR}/out" produced)
  if(update)
    file(REMOVE_RECURSE "${expected_dir}")
    foreach(f IN LISTS produced)
      configure_file("${WORK_DIR}/out/${f}" "${expected_dir}/${f}" COPYONLY)
    endforeach()
  else()
    list_files("${expected_dir}" wanted)
    if(NOT wanted)
      fail("no golden files in ${expected_dir}")
    endif()
    foreach(f IN LISTS wanted)
      if(NOT EXISTS "${WORK_DIR}/out/${f}")
        fail("twinpost did not write ${f} (expected ${expected_dir}/${f})")
      else()
        check_text("${WORK_DIR}/out/${f}" "${expected_dir}/${f}" "${f}" OFF)
      endif()
    endforeach()
    foreach(f IN LISTS produced)
      list(FIND wanted "${f}" at)
      if(at EQUAL -1)
        fail("twinpost wrote ${f}, which is not expected (no ${expected_dir}/${f})")
      endif()
    endforeach()
  endif()
elseif(MODE STREQUAL "post-fail")
  # A failed run leaves nothing behind: no program, no temporary folder.
  list_files("${WORK_DIR}/out" produced)
  if(produced)
    string(REPLACE ";" ", " produced "${produced}")
    fail("the failed post wrote files: ${produced}")
  endif()
endif()

# The same post with its check after the writing (--threads 1) must give the same output,
# byte for byte, as the default, which checks on a second thread while it writes
# (post/concurrent_check.hpp): the exit code, stdout, stderr and every file.
if((MODE STREQUAL "post" OR MODE STREQUAL "post-fail") AND NOT update)
  set(one "${WORK_DIR}/one-thread")
  file(MAKE_DIRECTORY "${one}")
  file(GLOB inputs LIST_DIRECTORIES false RELATIVE "${WORK_DIR}" "${WORK_DIR}/*")
  foreach(f IN LISTS inputs)
    if(NOT f MATCHES "^(actual\\..*|empty\\.txt)$")
      configure_file("${WORK_DIR}/${f}" "${one}/${f}" COPYONLY)
    endif()
  endforeach()
  execute_process(COMMAND ${command} --threads 1
                  WORKING_DIRECTORY "${one}"
                  RESULT_VARIABLE one_rc
                  OUTPUT_FILE "${one}/actual.stdout"
                  ERROR_FILE "${one}/actual.stderr")
  if(NOT "${one_rc}" STREQUAL "${rc}")
    fail("--threads 1: exit code ${one_rc}, the default's ${rc}")
  endif()
  list_files("${WORK_DIR}/out" two_files)
  list_files("${one}/out" one_files)
  if(NOT "${one_files}" STREQUAL "${two_files}")
    fail("--threads 1 wrote '${one_files}', the default '${two_files}'")
  endif()
  foreach(f actual.stdout actual.stderr)
    check_text("${one}/${f}" "${WORK_DIR}/${f}" "--threads 1 ${f}" OFF)
  endforeach()
  foreach(f IN LISTS one_files)
    if(EXISTS "${WORK_DIR}/out/${f}")
      check_text("${one}/out/${f}" "${WORK_DIR}/out/${f}" "--threads 1 out/${f}" OFF)
    endif()
  endforeach()
endif()

if(failures)
  # Indented lines are printed as they are (CMake would re-flow the others).
  string(REPLACE "\n" "\n    " failures "    ${failures}")
  message(FATAL_ERROR "golden test failed\n  command: ${shown_command}\n  in: ${WORK_DIR}\n${failures}")
elseif(update)
  message(STATUS "golden files updated from: ${shown_command} (in ${WORK_DIR})")
else()
  message(STATUS "ok: ${shown_command}")
endif()
