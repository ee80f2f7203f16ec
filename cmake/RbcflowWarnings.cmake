# Warnings for project code only (third-party headers are included as SYSTEM by their targets).
function(rbcflow_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local)
  if(RBCFLOW_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

if(RBCFLOW_SANITIZE)
  # -UNDEBUG keeps assertions (Eigen's bounds and size checks included) in this build.
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined -UNDEBUG)
  add_link_options(-fsanitize=address,undefined)
endif()
