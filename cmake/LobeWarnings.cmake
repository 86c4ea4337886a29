# lobe_warnings(target): the project's warning set, applied to every first-party target.
function(lobe_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local
                         -Wno-unused-parameter -Wno-missing-field-initializers)
endfunction()
