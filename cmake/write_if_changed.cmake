# bcot_write_if_changed(<path> <text>): writes `text` to `path` only when the file's content
# differs, so generated sources keep their timestamp and are not recompiled needlessly.
# Included by the generator scripts run with `cmake -P`.
function(bcot_write_if_changed path text)
  set(old "")
  if(EXISTS "${path}")
    file(READ "${path}" old)
  endif()
  if(NOT old STREQUAL text)
    file(WRITE "${path}" "${text}")
  endif()
endfunction()
