#include "sylva/render/viewer/Viewer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

#include "ScriptPlayer.h"
#include "ViewerInput.h"
#include "ViewerOverlay.h"
#include "ViewerPanels.h"
#include "ViewerSession.h"
#include "WindowBlit.h"

namespace sylva::render {
namespace {

constexpr double kFilePollSeconds = 0.25;  // hot-reload polling in the interactive loop
constexpr double kIdleWaitSeconds = 0.25;  // event wait while nothing changes
constexpr double kLookRadiansPerPixel = 0.004;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// `frame` enlarged bilinearly (on the 8-bit sRGB values: it only stands in while the
// budget lowers the resolution) to width x height, so the overlay's text is drawn at
// the window's size.
RgbaImage enlarged(const Image& frame, int width, int height) {
    RgbaImage out(width, height);
    const double sx = double(frame.width) / width, sy = double(frame.height) / height;
    for (int y = 0; y < height; ++y) {
        const double fy = std::clamp((y + 0.5) * sy - 0.5, 0.0, frame.height - 1.0);
        const int y0 = int(fy), y1 = std::min(y0 + 1, frame.height - 1);
        const double wy = fy - y0;
        for (int x = 0; x < width; ++x) {
            const double fx = std::clamp((x + 0.5) * sx - 0.5, 0.0, frame.width - 1.0);
            const int x0 = int(fx), x1 = std::min(x0 + 1, frame.width - 1);
            const double wx = fx - x0;
            const auto texel = [&](int ix, int iy, int c) {
                return double(frame.pixels[(std::size_t(iy) * frame.width + ix) * 4 + c]);
            };
            std::uint8_t* q = out.at(x, y);
            for (int c = 0; c < 4; ++c) {
                const double top = texel(x0, y0, c) + wx * (texel(x1, y0, c) - texel(x0, y0, c));
                const double bottom = texel(x0, y1, c) + wx * (texel(x1, y1, c) - texel(x0, y1, c));
                q[c] = std::uint8_t(std::lround(top + wy * (bottom - top)));
            }
        }
    }
    return out;
}

}  // namespace

class Viewer::State {
public:
    State(BatchRenderer& batch, ViewerHost& host, ViewerOptions options)
        : options_(std::move(options)),
          session_(batch, host, options_),
          context_(batch.context()) {}

    Status run() {
        if (Status started = session_.start(); !started) {
            return started;
        }
        const bool window = context_ != nullptr && context_->nativeWindow() != nullptr;
        if (window) {
            input_ = std::make_unique<ViewerInput>(context_->nativeWindow());
            panels_ = std::make_unique<ViewerPanels>(context_->nativeWindow());
            input_->setCaptures([this] { return panels_->wantsMouse(); },
                                [this] { return panels_->wantsKeyboard(); });
            updateFrameSize();
        }
        ScriptPlayer player(session_, [this, window] {
            if (window) {
                show();
            }
        });
        if (Status played = player.run(options_.script); !played) {
            return played;
        }
        if (!window || player.quit() || options_.closeAfterScript) {
            return {};
        }
        interact();
        return {};
    }

private:
    void updateFrameSize() {
        int width = 0, height = 0;
        context_->framebufferSize(width, height);
        session_.setFrameSize(width, height);
    }

    // The last frame with the overlay, on the screen.
    void show() {
        const Image& frame = session_.image();
        if (frame.width <= 0) {
            return;
        }
        int width = 0, height = 0;
        context_->framebufferSize(width, height);
        RgbaImage shown;
        if (frame.width < width && frame.height < height) {
            shown = enlarged(frame, width, height);
        } else {
            shown.width = frame.width;
            shown.height = frame.height;
            shown.pixels = frame.pixels;
        }
        ViewerOverlay::draw(shown, session_.statusLines(),
                            help_ ? ViewerOverlay::helpLines() : std::vector<std::string>{},
                            message_, session_.error());
        blit_.show(shown, width, height);
        if (panels_) {
            panels_->draw(session_, message_);
        }
        context_->swapBuffers();
    }

    // Single key presses; false on quit.
    bool handle(const ViewerEvent& event) {
        Status done;
        switch (event.command) {
            case ViewerCommand::Quit:
                return false;
            case ViewerCommand::CycleMode:
                session_.cycleMode();
                break;
            case ViewerCommand::Camera:
                done = session_.goToCamera(static_cast<std::size_t>(event.number));
                break;
            case ViewerCommand::NextScenario:
                done = session_.nextScenario();
                break;
            case ViewerCommand::TimeBack:
                session_.shiftTime(-3600.0);
                break;
            case ViewerCommand::TimeForward:
                session_.shiftTime(3600.0);
                break;
            case ViewerCommand::ToggleHelp:
                help_ = !help_;
                show();
                break;
            case ViewerCommand::SaveCamera:
                done = session_.saveCamera("viewer_" + std::to_string(++saved_), "");
                message_ = done ? "saved camera viewer_" + std::to_string(saved_) : "";
                break;
            case ViewerCommand::Pick:
                message_ = session_.pick(event.x, event.y);
                show();
                break;
            case ViewerCommand::Quality:
                session_.changeQuality(event.number);
                break;
        }
        if (!done) {
            message_ = done.error().message;
            show();
        }
        return true;
    }

    void applyMotion(const Motion& motion) {
        const double speed = session_.speed();
        if (motion.forward != 0 || motion.right != 0 || motion.up != 0) {
            session_.move(motion.forward * speed, motion.right * speed, motion.up * speed);
        }
        if (motion.yaw != 0 || motion.pitch != 0) {
            session_.turn(motion.yaw, motion.pitch);
        }
        if (motion.dragX != 0 || motion.dragY != 0) {
            if (mode() == NavigationMode::Orbit) {
                session_.dragGlobe(motion.dragX, motion.dragY);
            } else {
                session_.turn(motion.dragX * kLookRadiansPerPixel,
                              -motion.dragY * kLookRadiansPerPixel);
            }
        }
        if (motion.zoom != 0) {
            session_.zoom(motion.zoom);
        }
    }

    NavigationMode mode() const { return session_.mode(); }

    void interact() {
        auto lastFrame = std::chrono::steady_clock::now();
        auto lastPoll = lastFrame;
        while (!context_->shouldClose()) {
            context_->pollEvents();
            updateFrameSize();
            const double seconds = std::min(secondsSince(lastFrame), 0.25);
            lastFrame = std::chrono::steady_clock::now();
            for (const ViewerEvent& event : input_->takeEvents()) {
                if (!handle(event)) {
                    return;
                }
            }
            applyMotion(input_->motion(seconds));
            if (secondsSince(lastPoll) > kFilePollSeconds) {
                session_.pollFiles();
                lastPoll = std::chrono::steady_clock::now();
            }
            if (!session_.needsFrame()) {
                // Nothing changes: sleep until input arrives (or the next file poll), then
                // redraw the panels over the last frame (no scene rendering).
                context_->waitEvents(kIdleWaitSeconds);
                lastFrame = std::chrono::steady_clock::now();
                show();
                continue;
            }
            if (!session_.changed() && !session_.waitForTiles(0.03)) {
                // Only tiles arriving, none new yet (or the last frame just ended): poll
                // the input again rather than redraw the same view.
                continue;
            }
            (void)session_.renderFrame(false);
            show();
        }
    }

    ViewerOptions options_;
    ViewerSession session_;
    GlContext* context_;
    // Panels after input: their GLFW callbacks chain to the input's and go first.
    std::unique_ptr<ViewerInput> input_;
    std::unique_ptr<ViewerPanels> panels_;
    WindowBlit blit_;
    bool help_ = true;
    std::string message_;
    int saved_ = 0;
};

Viewer::Viewer(BatchRenderer& batch, ViewerHost& host, ViewerOptions options)
    : state_(std::make_unique<State>(batch, host, std::move(options))) {}

Viewer::~Viewer() = default;

Status Viewer::run() {
    return state_->run();
}

}  // namespace sylva::render
