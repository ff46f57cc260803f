#include "ViewerPanels.h"

#include <imgui.h>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <vector>

namespace sylva::render {
namespace {

// 2024-01-01T00:00:00Z: the time slider's year (a leap year: day 172 is 21 June).
constexpr double kYearStartUtc = 1704067200.0;
const char* const kComparisonNames[] = {"off", "swipe", "blend", "side by side",
                                        "difference (CIEDE2000)"};
const ComparisonMode kComparisonModes[] = {ComparisonMode::None, ComparisonMode::Swipe,
                                           ComparisonMode::Blend, ComparisonMode::SideBySide,
                                           ComparisonMode::Difference};

// A combo box over `names`; returns whether the choice changed.
bool chooser(const char* label, const std::vector<std::string>& names, int& index) {
    index = std::clamp(index, 0, std::max(int(names.size()) - 1, 0));
    bool changed = false;
    const char* shown = names.empty() ? "" : names[std::size_t(index)].c_str();
    if (ImGui::BeginCombo(label, shown[0] != '\0' ? shown : "(default)")) {
        for (int i = 0; i < int(names.size()); ++i) {
            const bool selected = i == index;
            const std::string& name = names[std::size_t(i)];
            if (ImGui::Selectable(name.empty() ? "(default)" : name.c_str(), selected)) {
                changed = i != index;
                index = i;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

}  // namespace

ViewerPanels::ViewerPanels(void* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the project
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.92f;
    // Installs ImGui's callbacks, chained to ViewerInput's installed before.
    ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow*>(window), true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
}

ViewerPanels::~ViewerPanels() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

bool ViewerPanels::wantsMouse() const {
    return ImGui::GetIO().WantCaptureMouse;
}

bool ViewerPanels::wantsKeyboard() const {
    return ImGui::GetIO().WantCaptureKeyboard;
}

void ViewerPanels::draw(ViewerSession& session, const std::string& message) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(8, 60), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Sylva")) {
        viewPanel(session);
        comparePanel(session);
        layersAndTimePanel(session);
        statsPanel(session, message);
    }
    ImGui::End();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void ViewerPanels::viewPanel(ViewerSession& session) {
    if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
        return;
    }
    const std::vector<std::string> scenarios = session.scenarioNames();
    int current =
        int(std::find(scenarios.begin(), scenarios.end(), session.scenario()) - scenarios.begin());
    if (chooser("scenario", scenarios, current)) {
        (void)session.setScenario(scenarios[std::size_t(current)]);
    }
    int mode = static_cast<int>(session.mode());
    ImGui::RadioButton("orbit", &mode, 0);
    ImGui::SameLine();
    ImGui::RadioButton("fly", &mode, 1);
    ImGui::SameLine();
    ImGui::RadioButton("walk", &mode, 2);
    if (mode != static_cast<int>(session.mode())) {
        session.setMode(static_cast<NavigationMode>(mode));
    }
    const std::vector<std::string> cameras = session.cameraNames();
    for (std::size_t i = 0; i < cameras.size(); ++i) {
        if (i % 3 != 0) {
            ImGui::SameLine();
        }
        if (ImGui::Button(cameras[i].c_str())) {
            (void)session.goToCamera(cameras[i]);
        }
    }
}

void ViewerPanels::comparePanel(ViewerSession& session) {
    if (!ImGui::CollapsingHeader("Compare")) {
        return;
    }
    const std::vector<std::string> scenarios = session.scenarioNames();
    bool changed =
        ImGui::Combo("mode", &comparisonMode_, kComparisonNames, IM_ARRAYSIZE(kComparisonNames));
    changed = chooser("with", scenarios, otherScenario_) || changed;
    changed = ImGui::SliderFloat("split / amount", &amount_, 0.0f, 1.0f) || changed;
    if (changed && !scenarios.empty()) {
        (void)session.setComparison(kComparisonModes[comparisonMode_],
                                    scenarios[std::size_t(otherScenario_)], amount_);
    }
}

void ViewerPanels::layersAndTimePanel(ViewerSession& session) {
    if (ImGui::CollapsingHeader("Layers", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (const char* layer : {"colour", "vegetation", "atmosphere"}) {
            bool on = session.layerOn(layer);
            if (ImGui::Checkbox(layer, &on)) {
                (void)session.setLayer(layer, on);
            }
        }
        quality_ = float(session.qualityScale());
        if (ImGui::SliderFloat("vegetation quality", &quality_, 0.1f, 4.0f, "%.2f",
                               ImGuiSliderFlags_Logarithmic)) {
            session.setQualityScale(quality_);
        }
    }
    if (ImGui::CollapsingHeader("Time", ImGuiTreeNodeFlags_DefaultOpen)) {
        bool changed = ImGui::Checkbox("sun from date and time", &timeOn_);
        changed = ImGui::SliderInt("day of 2024", &dayOfYear_, 1, 366) || changed;
        changed = ImGui::SliderFloat("hour (UTC)", &hourUtc_, 0.0f, 24.0f, "%.2f") || changed;
        if (changed) {
            if (timeOn_) {
                session.setTime(kYearStartUtc + (dayOfYear_ - 1) * 86400.0 + hourUtc_ * 3600.0);
            } else {
                session.clearTime();
            }
        }
    }
}

void ViewerPanels::statsPanel(const ViewerSession& session, const std::string& message) {
    if (!ImGui::CollapsingHeader("Stats", ImGuiTreeNodeFlags_DefaultOpen)) {
        return;
    }
    for (const std::string& line : session.statusLines()) {
        ImGui::TextWrapped("%s", line.c_str());
    }
    if (!message.empty()) {
        ImGui::TextWrapped("%s", message.c_str());
    }
}

}  // namespace sylva::render
