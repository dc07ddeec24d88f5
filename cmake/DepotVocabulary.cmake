# Trains the default vocabulary (called by the depot_vocabulary target):
# renders two short depot sequences (seeds the tests and benchmarks do not
# use), then `depot slam vocabulary train` on them, the shared photos and
# opencv-doc's sample images. Everything comes from this machine.
set(samples /usr/share/doc/opencv-doc/examples/data)
if(NOT IS_DIRECTORY ${samples})
  message(FATAL_ERROR "${samples}: missing; install Debian's opencv-doc (tools/install-deps.sh)")
endif()
if(NOT IS_DIRECTORY ${SHARED_DATA}/photos)
  message(FATAL_ERROR "${SHARED_DATA}/photos: missing; set DEPOT_SHARED_DATA")
endif()
get_filename_component(work ${OUTPUT} DIRECTORY)
set(render ${work}/render)
file(REMOVE_RECURSE ${render})
file(MAKE_DIRECTORY ${render})
set(datasets)
foreach(scenario depot_static depot_walking_halfsphere)
  execute_process(
    COMMAND ${DEPOT} sim render ${SOURCE_DIR}/scenarios/${scenario}.yaml -o ${render}/${scenario}
            --frames 240 --seed 101
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "rendering ${scenario} for the vocabulary failed")
  endif()
  list(APPEND datasets --dataset ${render}/${scenario})
endforeach()
execute_process(
  COMMAND ${DEPOT} slam vocabulary train -o ${OUTPUT} --images ${SHARED_DATA}/photos
          --images ${samples} ${datasets} --dataset-every 4 --quiet
  RESULT_VARIABLE rc)
file(REMOVE_RECURSE ${render})
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "training the vocabulary failed")
endif()
