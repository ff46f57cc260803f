#include "ViewerInput.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <utility>

namespace sylva::render {
namespace {

ViewerInput* inputOf(GLFWwindow* window) {
    return static_cast<ViewerInput*>(glfwGetWindowUserPointer(window));
}

void keyCallback(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
    inputOf(window)->onKey(key, action, mods);
}
void buttonCallback(GLFWwindow* window, int button, int action, int /*mods*/) {
    inputOf(window)->onButton(button, action);
}
void cursorCallback(GLFWwindow* window, double x, double y) {
    inputOf(window)->onCursor(x, y);
}
void scrollCallback(GLFWwindow* window, double /*x*/, double y) {
    inputOf(window)->onScroll(y);
}

}  // namespace

ViewerInput::ViewerInput(void* window) : window_(window) {
    auto* glfwWindow = static_cast<GLFWwindow*>(window_);
    glfwSetWindowUserPointer(glfwWindow, this);
    glfwSetKeyCallback(glfwWindow, keyCallback);
    glfwSetMouseButtonCallback(glfwWindow, buttonCallback);
    glfwSetCursorPosCallback(glfwWindow, cursorCallback);
    glfwSetScrollCallback(glfwWindow, scrollCallback);
}

ViewerInput::~ViewerInput() {
    auto* glfwWindow = static_cast<GLFWwindow*>(window_);
    glfwSetKeyCallback(glfwWindow, nullptr);
    glfwSetMouseButtonCallback(glfwWindow, nullptr);
    glfwSetCursorPosCallback(glfwWindow, nullptr);
    glfwSetScrollCallback(glfwWindow, nullptr);
    glfwSetWindowUserPointer(glfwWindow, nullptr);
}

void ViewerInput::setCaptures(std::function<bool()> mouse, std::function<bool()> keyboard) {
    mouseCaptured_ = std::move(mouse);
    keyboardCaptured_ = std::move(keyboard);
}

void ViewerInput::onKey(int key, int action, int /*mods*/) {
    if (action != GLFW_PRESS || (keyboardCaptured_ && keyboardCaptured_())) {
        return;
    }
    ViewerEvent event;
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
        event.command = ViewerCommand::Camera;
        event.number = key - GLFW_KEY_1;
    } else {
        switch (key) {
            case GLFW_KEY_TAB:
                event.command = ViewerCommand::CycleMode;
                break;
            case GLFW_KEY_N:
                event.command = ViewerCommand::NextScenario;
                break;
            case GLFW_KEY_T:
                event.command = ViewerCommand::TimeBack;
                break;
            case GLFW_KEY_Y:
                event.command = ViewerCommand::TimeForward;
                break;
            case GLFW_KEY_H:
            case GLFW_KEY_F1:
                event.command = ViewerCommand::ToggleHelp;
                break;
            case GLFW_KEY_P:
                event.command = ViewerCommand::SaveCamera;
                break;
            case GLFW_KEY_LEFT_BRACKET:
                event.command = ViewerCommand::Quality;
                event.number = -1;
                break;
            case GLFW_KEY_RIGHT_BRACKET:
                event.command = ViewerCommand::Quality;
                event.number = 1;
                break;
            case GLFW_KEY_ESCAPE:
                event.command = ViewerCommand::Quit;
                break;
            default:
                return;
        }
    }
    events_.push_back(event);
}

void ViewerInput::onButton(int button, int action) {
    if (action == GLFW_PRESS && mouseCaptured_ && mouseCaptured_()) {
        return;  // a click on a panel
    }
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
        dragging_ = action == GLFW_PRESS;
    } else if (button == GLFW_MOUSE_BUTTON_RIGHT && action == GLFW_PRESS) {
        // Cursor positions are in screen coordinates; the pick needs framebuffer pixels.
        auto* window = static_cast<GLFWwindow*>(window_);
        int windowWidth = 1, windowHeight = 1, width = 1, height = 1;
        glfwGetWindowSize(window, &windowWidth, &windowHeight);
        glfwGetFramebufferSize(window, &width, &height);
        ViewerEvent event;
        event.command = ViewerCommand::Pick;
        event.x = cursorX_ * width / std::max(windowWidth, 1);
        event.y = cursorY_ * height / std::max(windowHeight, 1);
        events_.push_back(event);
    }
}

void ViewerInput::onCursor(double x, double y) {
    if (dragging_) {
        dragX_ += x - cursorX_;
        dragY_ += y - cursorY_;
    }
    cursorX_ = x;
    cursorY_ = y;
}

void ViewerInput::onScroll(double y) {
    if (mouseCaptured_ && mouseCaptured_()) {
        return;
    }
    scroll_ += y;
}

Motion ViewerInput::motion(double seconds) {
    auto* window = static_cast<GLFWwindow*>(window_);
    const bool keyboard = !(keyboardCaptured_ && keyboardCaptured_());
    auto held = [&](int key) {
        return keyboard && glfwGetKey(window, key) == GLFW_PRESS ? 1.0 : 0.0;
    };
    const double fast = (held(GLFW_KEY_LEFT_SHIFT) + held(GLFW_KEY_RIGHT_SHIFT)) > 0 ? 5.0 : 1.0;
    Motion motion;
    const double step = seconds * fast;
    motion.forward = (held(GLFW_KEY_W) - held(GLFW_KEY_S)) * step;
    motion.right = (held(GLFW_KEY_D) - held(GLFW_KEY_A)) * step;
    motion.up = (held(GLFW_KEY_E) - held(GLFW_KEY_Q)) * step;
    constexpr double kTurnRate = 1.0;  // radians per second with the arrow keys
    motion.yaw = (held(GLFW_KEY_RIGHT) - held(GLFW_KEY_LEFT)) * kTurnRate * seconds;
    motion.pitch = (held(GLFW_KEY_UP) - held(GLFW_KEY_DOWN)) * kTurnRate * seconds;
    motion.dragX = dragX_;
    motion.dragY = dragY_;
    motion.zoom = scroll_;
    dragX_ = dragY_ = scroll_ = 0;
    return motion;
}

std::vector<ViewerEvent> ViewerInput::takeEvents() {
    std::vector<ViewerEvent> events;
    events.swap(events_);
    return events;
}

}  // namespace sylva::render
