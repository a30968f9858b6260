# Compiles every generated .java file under SRC into OUT (the list is only known after
# lcm-gen ran, hence a script rather than a fixed source list).
file(GLOB_RECURSE _java ${SRC}/*.java)
execute_process(COMMAND ${JAVAC} -nowarn -cp ${CP} -d ${OUT} ${_java} RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "javac failed")
endif()
