# Patches the C++ headers lcm-gen 1.3 wrote into DIR: its string decoder
# accepts a negative length, which passes the bounds check and then makes
# `len - 1` overflow (undefined behaviour; a copy of up to 2 GB past the
# datagram). Found by fuzz/message_fuzzer.cpp. Every encoded string has
# length >= 1 (its terminating NUL), so that is required. The same holds for
# an element of a string array (`__elem_len`, robot_description_t's
# joint_names; found by the fuzzer when that type was added).
file(GLOB headers "${DIR}/*.hpp")
foreach(header ${headers})
  file(READ "${header}" text)
  string(REGEX REPLACE "if\\(__([A-Za-z0-9_]+)_len__ > maxlen - pos\\) return -1;"
                       "if(__\\1_len__ < 1 || __\\1_len__ > maxlen - pos) return -1;" patched "${text}")
  string(REPLACE "if(__elem_len > maxlen - pos) return -1;"
                 "if(__elem_len < 1 || __elem_len > maxlen - pos) return -1;" patched "${patched}")
  if(NOT patched STREQUAL text)
    file(WRITE "${header}" "${patched}")
  endif()
endforeach()
