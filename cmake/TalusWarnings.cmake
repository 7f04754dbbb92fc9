# Our own code builds warning-free with the strict set; third-party headers
# are included as SYSTEM so their warnings do not stop the build.
function(talus_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Werror)
endfunction()
