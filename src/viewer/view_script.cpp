#include "proxima/viewer/view_script.h"

#include <charconv>

#include "proxima/core/error.h"
#include "proxima/viewer/viewer_session.h"

namespace proxima {

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t i = 0; i <= s.size(); ++i)
    if (i == s.size() || s[i] == sep) {
      out.push_back(s.substr(start, i - start));
      start = i + 1;
    }
  return out;
}

}  // namespace

std::vector<ScriptFrame> parse_view_script(const std::string& text, const char* flag) {
  std::vector<ScriptFrame> frames;
  std::vector<std::string> pending_shots;  // shot: before any frame
  for (const std::string& token : split(text, ',')) {
    if (token.empty()) continue;
    const std::vector<std::string> f = split(token, ':');
    auto bad = [&](const std::string& why) -> void {
      fail_input(std::string(flag) + ": '" + token + "': " + why);
    };
    auto number = [&](size_t i, double lo, double hi) {
      if (i >= f.size()) bad("missing a number");
      double v = 0.0;
      const char* b = f[i].data();
      const auto [end, ec] = std::from_chars(b, b + f[i].size(), v);
      if (ec != std::errc() || end != b + f[i].size() || !(v >= lo && v <= hi))
        bad("expected a number in [" + std::to_string(int(lo)) + ", " + std::to_string(int(hi)) + "]");
      return v;
    };
    auto arity = [&](size_t n) {
      if (f.size() != n) bad("expected " + std::to_string(n - 1) + " argument(s)");
    };
    const std::string& op = f[0];
    if (op == "hold") {
      arity(3);
      if (f[1].empty()) bad("missing the key");
      const int n = int(number(2, 1, 100000));
      for (int i = 0; i < n; ++i) frames.push_back({});
      frames[frames.size() - size_t(n)].before.push_back({ViewEvent::Type::KeyDown, f[1]});
      frames.back().after.push_back({ViewEvent::Type::KeyUp, f[1]});
    } else if (op == "press") {
      arity(2);
      if (f[1].empty()) bad("missing the key");
      frames.push_back({{{ViewEvent::Type::KeyDown, f[1]}, {ViewEvent::Type::KeyUp, f[1]}}, {}, {}});
    } else if (op == "mouse") {
      arity(3);
      frames.push_back({{{ViewEvent::Type::Mouse, "", vec2(float(number(1, -1e5, 1e5)), float(number(2, -1e5, 1e5)))}}, {}, {}});
    } else if (op == "scroll") {
      arity(2);
      frames.push_back({{{ViewEvent::Type::Scroll, "", vec2(float(number(1, -100, 100)), 0.0f)}}, {}, {}});
    } else if (op == "resize") {
      arity(3);
      frames.push_back({{{ViewEvent::Type::Resize, "", vec2(float(number(1, 16, 8192)), float(number(2, 16, 8192)))}}, {}, {}});
    } else if (op == "idle") {
      arity(2);
      const int n = int(number(1, 1, 100000));
      for (int i = 0; i < n; ++i) frames.push_back({});
    } else if (op == "shot") {
      if (f.size() < 2 || token.size() <= 5) bad("missing the file");
      const std::string file = token.substr(5);  // file names may hold ':'
      if (frames.empty()) pending_shots.push_back(file);
      else frames.back().shots.push_back(file);
    } else if (op == "quit") {
      arity(1);
      frames.push_back({{{ViewEvent::Type::Quit, ""}}, {}, {}});
    } else {
      bad("unknown step (hold, press, mouse, scroll, resize, idle, shot, quit)");
    }
  }
  if (!pending_shots.empty()) {
    if (frames.empty()) frames.push_back({});
    frames.front().shots.insert(frames.front().shots.begin(), pending_shots.begin(), pending_shots.end());
  }
  return frames;
}

void apply_event(ViewerSession& session, const ViewEvent& e) {
  switch (e.type) {
    case ViewEvent::Type::KeyDown: session.key_down(e.key); break;
    case ViewEvent::Type::KeyUp: session.key_up(e.key); break;
    case ViewEvent::Type::Mouse: session.mouse_motion(e.value); break;
    case ViewEvent::Type::Scroll: session.scroll(e.value.x); break;
    case ViewEvent::Type::Resize: session.resize(int(e.value.x), int(e.value.y)); break;
    case ViewEvent::Type::Quit: session.key_down("escape"); break;
  }
}

}  // namespace proxima
