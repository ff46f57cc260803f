# sylva_warnings: an interface target every Sylva target links for its warning flags.
add_library(sylva_warnings INTERFACE)
target_compile_options(sylva_warnings INTERFACE -Wall -Wextra -Wshadow)
if(SYLVA_WERROR)
  target_compile_options(sylva_warnings INTERFACE -Werror)
endif()
