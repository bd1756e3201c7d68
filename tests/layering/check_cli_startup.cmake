# The centaur executable does not link libOSMesa (and its libLLVM): the renderer loads it when it first renders, so
# that the commands that do not render start without its ~0.1 s of relocations. Non-vacuous: ldd must list MuJoCo.
execute_process(COMMAND ldd "${CLI}" OUTPUT_VARIABLE libs RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT libs MATCHES "libmujoco")
  message(FATAL_ERROR "ldd ${CLI} failed or did not list MuJoCo (rc ${rc}):\n${libs}")
endif()
foreach(forbidden "libOSMesa" "libLLVM")
  string(FIND "${libs}" "${forbidden}" pos)
  if(NOT pos EQUAL -1)
    message(FATAL_ERROR "${CLI} loads ${forbidden} at start:\n${libs}")
  endif()
endforeach()
message(STATUS "centaur loads no GL library at start")
