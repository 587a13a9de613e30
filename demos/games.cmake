# The three games as libraries, for their programs (demos/CMakeLists.txt) and for the web page
# (web/CMakeLists.txt includes this file: game=airhockey, game=peggle, game=slingshot). Each
# game is two:
#   NAME_game  the level and the rules on fixstep::core (tests/demos/ check them without a window)
#   NAME_play  the game as fixstep::app runs it: NAME_app.hpp (the Game type and its
#              app::Settings) and the game's drawing (draw.cpp)
include_guard(GLOBAL)

# slingshot: drag the ball back on its band, let go, knock the targets off their ropes.
add_library(slingshot_game STATIC ${CMAKE_CURRENT_LIST_DIR}/slingshot/game.cpp)
target_link_libraries(slingshot_game PUBLIC fixstep::core PRIVATE fixstep_options)
target_include_directories(slingshot_game PUBLIC ${CMAKE_CURRENT_LIST_DIR}/slingshot)
add_library(slingshot_play STATIC ${CMAKE_CURRENT_LIST_DIR}/slingshot/draw.cpp)
target_link_libraries(slingshot_play PUBLIC slingshot_game fixstep::app PRIVATE fixstep_options)

# peggle: a Peggle-like (sensors, filters, a ray-cast aim guide, the game's own drawing).
add_library(peggle_game STATIC ${CMAKE_CURRENT_LIST_DIR}/peggle/game.cpp)
target_link_libraries(peggle_game PUBLIC fixstep::core PRIVATE fixstep_options)
target_include_directories(peggle_game PUBLIC ${CMAKE_CURRENT_LIST_DIR}/peggle)
add_library(peggle_play STATIC ${CMAKE_CURRENT_LIST_DIR}/peggle/draw.cpp)
target_link_libraries(peggle_play PUBLIC peggle_game fixstep::app PRIVATE fixstep_options)

# airhockey: two mallets, one puck; two players over the network (its program links
# fixstep::net_app: --host / --join), or one against the computer (its program, and the page).
add_library(airhockey_game STATIC ${CMAKE_CURRENT_LIST_DIR}/airhockey/game.cpp)
target_link_libraries(airhockey_game PUBLIC fixstep::core PRIVATE fixstep_options)
target_include_directories(airhockey_game PUBLIC ${CMAKE_CURRENT_LIST_DIR}/airhockey)
add_library(airhockey_play STATIC ${CMAKE_CURRENT_LIST_DIR}/airhockey/draw.cpp)
target_link_libraries(airhockey_play PUBLIC airhockey_game fixstep::app PRIVATE fixstep_options)

# stacker: drag the ball back on its band, let go, knock the towers of boxes (box shapes) down.
add_library(stacker_game STATIC ${CMAKE_CURRENT_LIST_DIR}/stacker/game.cpp)
target_link_libraries(stacker_game PUBLIC fixstep::core PRIVATE fixstep_options)
target_include_directories(stacker_game PUBLIC ${CMAKE_CURRENT_LIST_DIR}/stacker)
add_library(stacker_play STATIC ${CMAKE_CURRENT_LIST_DIR}/stacker/draw.cpp)
target_link_libraries(stacker_play PUBLIC stacker_game fixstep::app PRIVATE fixstep_options)
# pinball: two flippers (kinematic shapes driven by target_angle input), bumpers, a plunger.
add_library(pinball_game STATIC ${CMAKE_CURRENT_LIST_DIR}/pinball/game.cpp)
target_link_libraries(pinball_game PUBLIC fixstep::core PRIVATE fixstep_options)
target_include_directories(pinball_game PUBLIC ${CMAKE_CURRENT_LIST_DIR}/pinball)
add_library(pinball_play STATIC ${CMAKE_CURRENT_LIST_DIR}/pinball/draw.cpp)
target_link_libraries(pinball_play PUBLIC pinball_game fixstep::app PRIVATE fixstep_options)
# platformer: a character mover over one-way platforms, a moving platform and a crate.
add_library(platformer_game STATIC ${CMAKE_CURRENT_LIST_DIR}/platformer/game.cpp)
target_link_libraries(platformer_game PUBLIC fixstep::core PRIVATE fixstep_options)
target_include_directories(platformer_game PUBLIC ${CMAKE_CURRENT_LIST_DIR}/platformer)
add_library(platformer_play INTERFACE)
target_link_libraries(platformer_play INTERFACE platformer_game fixstep::app)
