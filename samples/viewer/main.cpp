// Sample: an interactive viewer. A GLFW window of the application's own
// (GL 4.3+ core), adopted with vds::GlContext::adoptCurrent(): the library
// bakes, uploads and draws in the window's context and never makes one of
// its own. The model is drawn clipped by and seen through solids through
// shaders/vds/styles.glsl, with the VDS, slicemaps, solid voxels or the
// exact classifier as inside test (the offline samples' scene code).
//
//   vds_viewer [MESH] [--solid SOLID.obj]... [--clip SPRITE.vds]... [--lens SOLID.obj] [--scene clip|lens|styles]
//              [--with vds|slicemap|slicemap-local|solid|exact] [--resolution N] [--size WxH] [--view iso|x|y|z]
//              [--script FILE]
//   (vds_viewer --help lists the keys and the script's commands)
//
// Mouse: left-drag moves the lens in the view plane, right-drag the clip
// solid; the scroll wheel scales the solid dragged last. Keys: 1-5 the
// inside test, B the outside style, L the lens style, K keep/cut, C union/
// intersection, R reset, P screenshot, Q or Escape quit. The inside test and
// the frame time are written at the top left (not in screenshots) and in the title.
//
// --script FILE drives the same handlers without a person, one command a line:
//   key K                  a key (a letter, a digit, or escape)
//   drag X0 Y0 X1 Y1 [left|right]   a drag in window pixels (top left is 0 0)
//   scroll N               N wheel steps (positive: larger) on the last-dragged solid
//   screenshot FILE.png    the next frame as drawn
//   wait N frames          N frames
//   quit                   (the end of the script quits too)
// Blank lines and lines starting with # are skipped.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <vds/error.h>
#include <vds/eval/image.h>
#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/mesh_io.h>
#include <vds/vds_file.h>

#include "scene.h"

namespace {

using vds::samples::Combine;
using vds::samples::Lookup;
using vds::samples::Role;
using vds::samples::Style;

struct Options {
    std::string mesh, scene, view = "iso", with = "vds", size = "640x480", script, lens;
    std::vector<std::string> clips, solids;
    std::uint32_t resolution = 128;
    int width = 640, height = 480;
};

struct Command {
    int line = 0;
    std::string verb;         // key, drag, scroll, screenshot, wait, quit
    int key = 0;              // GLFW key
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int button = GLFW_MOUSE_BUTTON_LEFT;
    int count = 0;            // scroll steps, wait frames
    std::string path;
};

// "A".."Z", "0".."9", "escape" -> a GLFW key; 0 if none.
int keyByName(std::string name) {
    if (name.size() == 1) {
        const char c = char(std::toupper(static_cast<unsigned char>(name[0])));
        if (c >= 'A' && c <= 'Z') return GLFW_KEY_A + (c - 'A');
        if (c >= '0' && c <= '9') return GLFW_KEY_0 + (c - '0');
    }
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return name == "escape" ? GLFW_KEY_ESCAPE : 0;
}

std::vector<Command> readScript(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw vds::IoError("cannot read script '" + path + "'");
    std::vector<Command> commands;
    std::string text;
    for (int number = 1; std::getline(in, text); ++number) {
        const auto fail = [&](const std::string& why) {
            throw vds::InvalidArgument(path + ":" + std::to_string(number) + ": " + why);
        };
        std::istringstream words(text);
        Command c;
        c.line = number;
        if (!(words >> c.verb) || c.verb[0] == '#') continue;
        std::string extra;
        if (c.verb == "key") {
            std::string name;
            if (!(words >> name) || !(c.key = keyByName(name))) fail("'key' takes a letter, a digit or escape");
        } else if (c.verb == "drag") {
            std::string button;
            if (!(words >> c.x0 >> c.y0 >> c.x1 >> c.y1)) fail("'drag' takes X0 Y0 X1 Y1 [left|right]");
            if (words >> button) {
                if (button == "right") c.button = GLFW_MOUSE_BUTTON_RIGHT;
                else if (button != "left") fail("drag button '" + button + "' is not left or right");
            }
        } else if (c.verb == "scroll") {
            if (!(words >> c.count)) fail("'scroll' takes a number of steps");
        } else if (c.verb == "screenshot") {
            if (!(words >> c.path)) fail("'screenshot' takes a file name");
        } else if (c.verb == "wait") {
            std::string unit;
            if (!(words >> c.count) || c.count < 0 || ((words >> unit) && unit != "frames" && unit != "frame"))
                fail("'wait' takes N frames");
        } else if (c.verb != "quit") {
            fail("unknown command '" + c.verb + "' (key, drag, scroll, screenshot, wait, quit)");
        }
        if (words >> extra) fail("unexpected '" + extra + "' after '" + c.verb + "'");
        commands.push_back(c);
    }
    return commands;
}

vds::samples::Scene buildScene(const Options& o) {
    using namespace vds::samples;
    const std::string data = VDS_SAMPLES_DATA;
    Scene scene;
    if (o.scene == "clip") scene = clipScene(data, Combine::Union);
    else if (o.scene == "lens") scene = lensScene(data);
    else if (o.scene == "styles") scene = stylesScene(data);
    else {
        scene.name = o.mesh.empty() ? data + "/spot.obj" : o.mesh;
        scene.model = vds::loadMesh(scene.name);
        for (const auto& path : o.clips) {
            SceneSolid solid;
            solid.name = path;
            solid.sprite = vds::readSprite(path);
            scene.solids.push_back(std::move(solid));
        }
        for (const auto& path : o.solids) {
            SceneSolid solid;
            solid.name = path;
            solid.mesh = vds::loadMesh(path);
            scene.solids.push_back(std::move(solid));
        }
        if (o.clips.empty() && o.solids.empty() && o.lens.empty()) {
            // Spot with the bundled sphere cutting the body and a lens at the head.
            scene.solids.push_back({"body-sphere", vds::loadMesh(data + "/lens.obj"), {}, glm::mat4(1.0f),
                                    Role::ClipAway, Style::Shaded});
            scene.solids.push_back({"lens", uvSphere(glm::vec3(0.0f), 0.42f, 24), {}, lensPath(0.0f), Role::Lens,
                                    Style::XRay});
            scene.baseStyle = Style::Gouraud;
            scene.viewDirection = {1.0f, 0.45f, 0.35f}; // the lens scene's
        }
        if (!o.lens.empty()) {
            scene.solids.push_back({o.lens, vds::loadMesh(o.lens), {}, glm::mat4(1.0f), Role::Lens, Style::XRay});
            scene.baseStyle = Style::Gouraud;
        }
    }
    if (o.view == "x") scene.viewDirection = {1, 0, 0};
    else if (o.view == "y") { scene.viewDirection = {0, 1, 0}; scene.up = {0, 0, -1}; }
    else if (o.view == "z") scene.viewDirection = {0, 0, 1};
    if (scene.solids.size() > 8) throw vds::InvalidArgument("at most 8 solids (--solid, --clip and --lens together)");
    return scene;
}

// A 3 x 5 pixel font for the overlay: five rows of three bits, top row first.
int glyph(char c) {
    static const std::pair<char, const char*> font[] = {
        {'0', "111101101101111"}, {'1', "010110010010111"}, {'2', "111001111100111"}, {'3', "111001111001111"},
        {'4', "101101111001001"}, {'5', "111100111001111"}, {'6', "111100111101111"}, {'7', "111001001001001"},
        {'8', "111101111101111"}, {'9', "111101111001111"}, {'.', "000000000000010"}, {'-', "000000111000000"},
        {'a', "000011101101011"}, {'c', "000111100100111"}, {'d', "001001111101111"}, {'e', "000111111100111"},
        {'i', "010000010010010"}, {'l', "110010010010111"}, {'m', "000111111101101"}, {'o', "000111101101111"},
        {'p', "000111101111100"}, {'s', "000011110011110"}, {'t', "010111010010011"}, {'v', "000101101101010"},
        {'x', "000101010101101"}};
    for (const auto& [ch, rows] : font)
        if (ch == c) {
            int bits = 0;
            for (int k = 0; k < 15; ++k) bits = bits << 1 | (rows[k] == '1');
            return bits;
        }
    return 0;
}

// Writes `text` at the window's top left: each font pixel a scissored clear
// (no program, no buffers), dark on a light box, `scale` pixels a font pixel.
void drawOverlay(const std::string& text, int height, int scale) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glEnable(GL_SCISSOR_TEST);
    const int left = 2 * scale, top = height - 2 * scale;
    glScissor(left - scale, top - 6 * scale, (int(text.size()) * 4 + 1) * scale, 7 * scale);
    glClearColor(0.93f, 0.93f, 0.90f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glClearColor(0.10f, 0.10f, 0.12f, 1.0f);
    for (std::size_t i = 0; i < text.size(); ++i) {
        const int bits = glyph(text[i]);
        for (int k = 0; k < 15; ++k)
            if (bits >> (14 - k) & 1) {
                glScissor(left + (int(i) * 4 + k % 3) * scale, top - (k / 3 + 1) * scale, scale, scale);
                glClear(GL_COLOR_BUFFER_BIT);
            }
    }
    glDisable(GL_SCISSOR_TEST);
}

class Viewer {
public:
    Viewer(GLFWwindow* window, const vds::samples::Scene& scene, Lookup lookup, std::uint32_t resolution)
        : window_(window), initial_(scene), scene_(scene), lookup_(lookup), resolution_(resolution),
          gl_(vds::GlContext::adoptCurrent()) {
        for (std::size_t i = 0; i < scene.solids.size(); ++i) {
            const Role role = scene.solids[i].role;
            if (role == Role::Lens && !lens_) lens_ = i;
            if ((role == Role::ClipAway || role == Role::ClipTo) && !clip_) clip_ = i;
        }
        active_ = lens_ ? *lens_ : clip_ ? *clip_ : 0;
        rebuild();
    }

    void key(int key) {
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_5) {
            const Lookup lookups[] = {Lookup::Vds, Lookup::Slicemap, Lookup::SlicemapLocal, Lookup::Solid, Lookup::Exact};
            const Lookup previous = lookup_;
            lookup_ = lookups[key - GLFW_KEY_1];
            try {
                rebuild();
            } catch (const vds::InvalidArgument& e) { // a sprite-only solid has no voxels
                std::fprintf(stderr, "vds_viewer: %s\n", e.what());
                lookup_ = previous;
                rebuild();
            }
        } else if (key == GLFW_KEY_B) {
            scene_.baseStyle = next(scene_.baseStyle);
            restyle();
        } else if (key == GLFW_KEY_L) {
            for (auto& solid : scene_.solids)
                if (solid.role == Role::Lens || solid.role == Role::Style) solid.style = next(solid.style);
            restyle();
        } else if (key == GLFW_KEY_K) {
            for (auto& solid : scene_.solids)
                if (solid.role == Role::ClipAway || solid.role == Role::ClipTo)
                    solid.role = solid.role == Role::ClipAway ? Role::ClipTo : Role::ClipAway;
            restyle();
        } else if (key == GLFW_KEY_C) {
            const Combine c = scene_.combineAway == Combine::Union ? Combine::Intersection : Combine::Union;
            scene_.combineAway = scene_.combineTo = c;
            restyle();
        } else if (key == GLFW_KEY_R) {
            scene_ = initial_;
            restyle();
            for (std::size_t i = 0; i < scene_.solids.size(); ++i) renderer_->place(i, scene_.solids[i].placement);
        } else if (key == GLFW_KEY_P) {
            char name[32];
            std::snprintf(name, sizeof name, "vds-viewer-%03d.png", screenshots_++);
            screenshot_ = name;
        } else if (key == GLFW_KEY_Q || key == GLFW_KEY_ESCAPE) {
            glfwSetWindowShouldClose(window_, GLFW_TRUE);
        }
    }

    void press(int button, double x, double y) {
        dragging_ = button == GLFW_MOUSE_BUTTON_LEFT ? lens_ : button == GLFW_MOUSE_BUTTON_RIGHT ? clip_ : std::nullopt;
        if (!dragging_ && (button == GLFW_MOUSE_BUTTON_LEFT || button == GLFW_MOUSE_BUTTON_RIGHT)) dragging_ = 0;
        if (dragging_) active_ = *dragging_;
        lastX_ = x;
        lastY_ = y;
    }
    void release() { dragging_.reset(); }

    // Moves the dragged solid by the cursor's motion, in the view plane.
    void move(double x, double y) {
        if (!dragging_) return;
        int w = 0, h = 0;
        glfwGetWindowSize(window_, &w, &h);
        if (w <= 0 || h <= 0) return;
        int fw = 0, fh = 0;
        glfwGetFramebufferSize(window_, &fw, &fh);
        const glm::mat4 toWorld = glm::inverse(renderer_->viewProjection(std::uint32_t(fw), std::uint32_t(fh)));
        const glm::vec4 ndc(2.0 * (x - lastX_) / w, -2.0 * (y - lastY_) / h, 0.0f, 0.0f);
        const glm::vec3 delta(toWorld * ndc);
        lastX_ = x;
        lastY_ = y;
        auto& solid = scene_.solids[*dragging_];
        solid.placement = glm::translate(glm::mat4(1.0f), delta) * solid.placement;
        renderer_->place(*dragging_, solid.placement);
    }

    // Scales the solid dragged last about its centre, 10 % a step.
    void scroll(double steps) {
        auto& solid = scene_.solids[active_];
        glm::vec3 centre(0.0f);
        if (!solid.mesh.positions.empty()) {
            const vds::Box box = vds::meshBounds(solid.mesh);
            centre = 0.5f * (box.lo + box.hi);
        }
        const glm::vec3 world(solid.placement * glm::vec4(centre, 1.0f));
        const float factor = float(std::pow(1.1, steps));
        solid.placement = glm::translate(glm::mat4(1.0f), world) * glm::scale(glm::mat4(1.0f), glm::vec3(factor)) *
                          glm::translate(glm::mat4(1.0f), -world) * solid.placement;
        renderer_->place(active_, solid.placement);
    }

    // Draws a frame into the window's back buffer, writes a pending
    // screenshot (the scene only), then the overlay: inside test and frame time.
    void frame(double milliseconds) {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        if (w <= 0 || h <= 0) return;
        renderer_->drawTo(0, std::uint32_t(w), std::uint32_t(h));
        if (!screenshot_.empty()) {
            vds::eval::Image image{std::uint32_t(w), std::uint32_t(h)};
            std::vector<std::uint8_t> pixels(image.rgba.size());
            glReadBuffer(GL_BACK);
            glPixelStorei(GL_PACK_ALIGNMENT, 1);
            glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
            const std::size_t row = std::size_t(w) * 4;
            for (int y = 0; y < h; ++y) std::memcpy(image.at(0, std::uint32_t(y)), &pixels[std::size_t(h - 1 - y) * row], row);
            vds::eval::writePng(image, screenshot_);
            std::printf("wrote %s: %dx%d, %s\n", screenshot_.c_str(), w, h, vds::samples::toString(lookup_));
            screenshot_.clear();
        }
        char text[64];
        std::snprintf(text, sizeof text, "%s %.1f ms", vds::samples::toString(lookup_), milliseconds);
        drawOverlay(text, h, h >= 400 ? 3 : 2);
    }

    void screenshotNextFrame(const std::string& path) { screenshot_ = path; }
    Lookup lookup() const { return lookup_; }
    const vds::GlContext& gl() const { return gl_; }

private:
    static Style next(Style s) { return Style(int(s) % 4 + 1); }

    void rebuild() {
        renderer_.reset();
        renderer_ = std::make_unique<vds::samples::SceneRenderer>(gl_, scene_, lookup_,
                                                                  vds::samples::RepresentationSize{resolution_, false});
    }
    void restyle() {
        for (std::size_t i = 0; i < scene_.solids.size(); ++i)
            renderer_->setRole(i, scene_.solids[i].role, scene_.solids[i].style);
        renderer_->setStyles(scene_.baseStyle, scene_.combineAway, scene_.combineTo);
    }

    GLFWwindow* window_;
    vds::samples::Scene initial_, scene_;
    Lookup lookup_;
    std::uint32_t resolution_;
    vds::GlContext gl_; // the window's context, adopted
    std::unique_ptr<vds::samples::SceneRenderer> renderer_;
    std::optional<std::size_t> lens_, clip_, dragging_;
    std::size_t active_ = 0;
    double lastX_ = 0, lastY_ = 0;
    std::string screenshot_;
    int screenshots_ = 0;
};

std::string glfwProblem;

// Runs a handler from a GLFW callback: an exception must not unwind through
// GLFW's C frames, so it is kept, the window closed, and rethrown by the loop.
template <typename F>
void guarded(GLFWwindow* window, F&& handler) {
    auto* failure = static_cast<std::exception_ptr*>(glfwGetWindowUserPointer(window));
    try {
        handler();
    } catch (...) {
        if (!*failure) *failure = std::current_exception();
        glfwSetWindowShouldClose(window, GLFW_TRUE);
    }
}
Viewer* theViewer = nullptr; // the one window's viewer, for the callbacks

int run(const Options& o) {
    const std::vector<Command> script = o.script.empty() ? std::vector<Command>{} : readScript(o.script);
    const vds::samples::Scene scene = buildScene(o);
    const Lookup lookup = vds::samples::parseLookup(o.with);

    glfwSetErrorCallback([](int, const char* text) { glfwProblem = text; });
    if (!glfwInit()) throw vds::GlUnavailable("cannot open a window: " + glfwProblem);
    struct Terminate {
        ~Terminate() { glfwTerminate(); }
    } terminate;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(o.width, o.height, "vds_viewer", nullptr, nullptr);
    if (!window) throw vds::GlUnavailable("cannot open a GL 4.3 core window: " + glfwProblem);
    glfwMakeContextCurrent(window);
    glfwSwapInterval(script.empty() ? 1 : 0);

    {
        Viewer viewer(window, scene, lookup, o.resolution);
        std::exception_ptr failure;
        theViewer = &viewer;
        glfwSetWindowUserPointer(window, &failure);
        glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
            if (action == GLFW_PRESS) guarded(w, [&] { theViewer->key(key); });
        });
        glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
            double x = 0, y = 0;
            glfwGetCursorPos(w, &x, &y);
            if (action == GLFW_PRESS) guarded(w, [&] { theViewer->press(button, x, y); });
            else theViewer->release();
        });
        glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
            guarded(w, [&] { theViewer->move(x, y); });
        });
        glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
            guarded(w, [&] { theViewer->scroll(dy); });
        });
        std::printf("vds_viewer: GL %s, %s; keys 1-5 inside test, B/L styles, K keep, C combine, R reset, Q quit\n",
                    viewer.gl().info().version.c_str(), viewer.gl().info().renderer.c_str());

        using Clock = std::chrono::steady_clock;
        std::vector<double> frameMs;
        std::size_t next = 0;
        int waiting = 0;
        auto last = Clock::now();
        double shownMs = 0.0; // median of the last 10 frames
        while (!glfwWindowShouldClose(window)) {
            glfwPollEvents();
            if (!o.script.empty() && waiting > 0) --waiting;
            else if (!o.script.empty()) {
                bool quit = next == script.size();
                for (; next < script.size(); ++next) {
                    const Command& c = script[next];
                    if (c.verb == "key") viewer.key(c.key);
                    else if (c.verb == "drag") {
                        viewer.press(c.button, c.x0, c.y0);
                        viewer.move(c.x1, c.y1);
                        viewer.release();
                    } else if (c.verb == "scroll") viewer.scroll(c.count);
                    else if (c.verb == "screenshot") {
                        viewer.screenshotNextFrame(c.path);
                        ++next;
                        break;
                    } else if (c.verb == "wait") {
                        waiting = c.count;
                        ++next;
                        break;
                    } else if (c.verb == "quit") {
                        quit = true;
                        break;
                    }
                }
                if (quit) glfwSetWindowShouldClose(window, GLFW_TRUE);
            }
            viewer.frame(shownMs);
            glfwSwapBuffers(window);
            const auto now = Clock::now();
            frameMs.push_back(std::chrono::duration<double, std::milli>(now - last).count());
            last = now;
            if (frameMs.size() % 10 == 0) {
                std::vector<double> recent(frameMs.end() - 10, frameMs.end());
                std::sort(recent.begin(), recent.end());
                shownMs = recent[5];
                char title[160];
                std::snprintf(title, sizeof title, "vds_viewer: %s, %.1f ms/frame", vds::samples::toString(viewer.lookup()),
                              recent[5]);
                glfwSetWindowTitle(window, title);
            }
        }
        if (!frameMs.empty()) {
            std::sort(frameMs.begin(), frameMs.end());
            std::printf("vds_viewer: %zu frames, median %.1f ms/frame\n", frameMs.size(), frameMs[frameMs.size() / 2]);
        }
        glfwSetKeyCallback(window, nullptr);
        glfwSetMouseButtonCallback(window, nullptr);
        glfwSetCursorPosCallback(window, nullptr);
        glfwSetScrollCallback(window, nullptr);
        theViewer = nullptr;
        if (failure) std::rethrow_exception(failure);
    } // the viewer's GL objects go while the window's context is still current
    glfwDestroyWindow(window);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app("An interactive viewer: MESH clipped by and seen through solids, in a GLFW window whose own GL\n"
                 "context the library adopts. Left-drag moves the lens, right-drag the clip solid, the wheel\n"
                 "scales the solid dragged last. Keys: 1 vds, 2 slicemap, 3 slicemap-local, 4 solid voxels,\n"
                 "5 exact; B outside style, L lens style, K keep/cut, C union/intersection, R reset,\n"
                 "P screenshot, Q/Escape quit. Frame time in the title.\n"
                 "Script lines: key K | drag X0 Y0 X1 Y1 [left|right] | scroll N | screenshot FILE.png |\n"
                 "wait N frames | quit   (# comments)",
                 "vds_viewer");
    app.get_formatter()->label("Usage", "usage");
    app.option_defaults()->always_capture_default();
    app.add_option("MESH", o.mesh, "mesh to render (OBJ, PLY, STL, OFF); default: the bundled Spot")->type_name("");
    app.add_option("--solid", o.solids, "a closed mesh that cuts MESH (right-drag moves it)")
        ->expected(1, 8)
        ->allow_extra_args(false)
        ->type_name("SOLID.obj");
    app.add_option("--clip", o.clips, "a baked sprite that cuts MESH (inside test vds only)")
        ->expected(1, 8)
        ->allow_extra_args(false)
        ->type_name("SPRITE.vds");
    app.add_option("--lens", o.lens, "a closed mesh seen through in X-ray (left-drag moves it)")->type_name("SOLID.obj");
    app.add_option("--scene", o.scene, "one of the gallery's scenes instead of MESH and solids")
        ->check(CLI::IsMember({"clip", "lens", "styles"}));
    app.add_option("--with", o.with, "inside test at the start")
        ->check(CLI::IsMember({"vds", "slicemap", "slicemap-local", "solid", "exact"}));
    app.add_option("--resolution", o.resolution, "texels or cells along a solid's longest side")
        ->check(CLI::Range(8u, 2048u));
    app.add_option("--size", o.size, "window size in pixels")->type_name("WxH");
    app.add_option("--view", o.view, "look along -x, -y, -z or diagonally")->check(CLI::IsMember({"iso", "x", "y", "z"}));
    app.add_option("--script", o.script, "run these commands, then quit")->type_name("FILE");
    try {
        app.parse(argc, argv);
        char x = 0, rest = 0;
        if (std::sscanf(o.size.c_str(), "%d%c%d%c", &o.width, &x, &o.height, &rest) != 3 || (x != 'x' && x != 'X') ||
            o.width < 16 || o.height < 16 || o.width > 8192 || o.height > 8192)
            throw CLI::ValidationError("--size", "'" + o.size + "' is not WxH with sides 16 to 8192");
        if (!o.scene.empty() && (!o.mesh.empty() || !o.solids.empty() || !o.clips.empty() || !o.lens.empty()))
            throw CLI::ValidationError("--scene", "a gallery scene takes no MESH, --solid, --clip or --lens");
        if (!o.clips.empty() && o.with != "vds")
            throw CLI::ValidationError("--clip", "sprites work with --with vds only; give the solid's mesh with --solid");
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        std::fprintf(stderr, "vds_viewer: %s (try 'vds_viewer --help')\n", e.what());
        return 1;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_viewer: error: %s\n", e.what());
        return 1;
    }
}
