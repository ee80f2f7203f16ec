# Warnings for project code only (third-party headers are included as SYSTEM by their targets).
function(rbcflow_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local)
  if(RBCFLOW_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

if(RBCFLOW_SANITIZE)
  # -UNDEBUG keeps assertions (Eigen's bounds and size checks included) in this build. -O1
  # (ASan's recommended level) and line tables only (-g1: stack traces keep files and lines)
  # halve the compile time, which the sanitizers dominate: tests/libsolver/linear/
  # test_anderson_mixing.cpp compiles in 133 s at -O2 -g, 65 s at -O1 -g1 (22 s in Release).
  # Coming after the build type's flags, these win over them.
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined -UNDEBUG -O1 -g1)
  add_link_options(-fsanitize=address,undefined)
endif()
