#include "probes/viewer/session_page.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "pd_core/geometry/tessellate_geometry.h"
#include "probes/trajectory/input_error.h"
#include "probes/viewer/viewer_assets.h"

namespace probes {
namespace {

// Compact JSON numbers: 6 significant digits (1 um at 1 m, 1 mN at 1 kN).
class JsonArray {
 public:
  explicit JsonArray(std::string* out) : out_(out) { *out_ += '['; }
  ~JsonArray() { *out_ += ']'; }
  void Add(double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.6g", std::isfinite(v) ? v : 0.0);
    Sep();
    *out_ += buf;
  }
  void AddInt(int64_t v) {
    Sep();
    *out_ += std::to_string(v);
  }
  void AddPose(const pd::Isometry3& X) {
    const pd::Quaternion q(X.linear());
    for (int i = 0; i < 3; ++i) Add(X.translation()[i]);
    Add(q.w()), Add(q.x()), Add(q.y()), Add(q.z());
  }
  void Sep() {
    if (!first_) *out_ += ',';
    first_ = false;
  }

 private:
  std::string* out_;
  bool first_ = true;
};

std::string Quoted(const std::string& s) {
  std::string j = nlohmann::json(s).dump();
  // Never let a name close the <script> element it sits in.
  for (size_t at = j.find("</"); at != std::string::npos; at = j.find("</", at)) j.replace(at, 2, "<\\/");
  return j;
}

void AppendMesh(std::string* o, const pd::TriangleMesh& mesh, const pd::Isometry3& X) {
  *o += "\"positions\":";
  {
    JsonArray a(o);
    for (const pd::Vector3& v : mesh.vertices) {
      const pd::Vector3 p = X * v;
      a.Add(p.x()), a.Add(p.y()), a.Add(p.z());
    }
  }
  *o += ",\"indices\":";
  JsonArray a(o);
  for (const Eigen::Vector3i& t : mesh.triangles) a.AddInt(t[0]), a.AddInt(t[1]), a.AddInt(t[2]);
}

std::string ReadAsset(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(path + ": cannot read three.js (Debian package libjs-three; --three-dir "
                            "names its directory)");
  }
  std::stringstream ss;
  ss << in.rdbuf();
  std::string s = ss.str();
  for (size_t at = s.find("</script"); at != std::string::npos; at = s.find("</script", at)) {
    s.replace(at, 2, "<\\/");
  }
  return s;
}

void Replace(std::string* page, const std::string& key, const std::string& value) {
  const size_t at = page->find(key);
  if (at == std::string::npos) throw std::logic_error("page template lacks " + key);
  page->replace(at, key.size(), value);
}

}  // namespace

void WriteSessionPage(std::ostream& out, const haptics::SceneConfig& config,
                      const haptics::SceneModels& models, const Session& session,
                      const RerenderedSession& rerendered, const PageOptions& options) {
  const std::string three = ReadAsset(options.three_dir + "/three.min.js");
  const std::string orbit = ReadAsset(options.three_dir + "/examples/js/controls/OrbitControls.js");

  // Frames kept: every stride-th pose, and the last one.
  const size_t n = session.frames.size();
  const size_t stride =
      options.max_frames > 0 ? std::max<size_t>(1, (n + options.max_frames - 1) / options.max_frames) : 1;
  std::vector<size_t> kept;
  for (size_t i = 0; i < n; i += stride) kept.push_back(i);
  if (kept.back() != n - 1) kept.push_back(n - 1);

  std::string j = "{";
  j += "\"scene\":" + Quoted(config.name) + ",\"config\":" + Quoted(config.file) +
       ",\"session\":" + Quoted(session.source) + ",\"format\":" + Quoted(session.format) +
       ",\"session_frames\":" + std::to_string(n);

  // Scene extent (for the size of half-space squares).
  double extent = 10 * models.tool->radius();
  for (const haptics::SceneObject& o : models.objects) {
    if (o.geometry->bounded()) extent = std::max(extent, o.X_WS.translation().norm() + o.geometry->radius());
  }
  j += ",\"objects\":[";
  for (size_t k = 0; k < models.objects.size(); ++k) {
    const haptics::SceneObject& o = models.objects[k];
    j += (k ? ",{" : "{");
    j += "\"name\":" + Quoted(o.name) + ",\"pose\":";
    { JsonArray a(&j); a.AddPose(o.X_WS); }
    if (o.geometry->bounded()) {
      j += ",\"kind\":\"mesh\",";
      AppendMesh(&j, pd::TessellateGeometry(*o.geometry), pd::Isometry3::Identity());
    } else {
      j += ",\"kind\":\"plane\",\"size\":" + std::to_string(2 * extent);
    }
    j += "}";
  }
  j += "],\"tool\":{\"radius\":" + std::to_string(models.tool->radius()) + ",";
  AppendMesh(&j, pd::TessellateGeometry(*models.tool), models.X_TG);
  j += "}";

  // Per frame. A pose left unanswered shows the last answer before it.
  std::string dev, tool, force, torque, t, depth, count, rtt, answered, flags, contacts;
  {
    JsonArray a_dev(&dev), a_tool(&tool), a_f(&force), a_tau(&torque), a_t(&t), a_d(&depth),
        a_c(&count), a_rtt(&rtt), a_ans(&answered), a_flags(&flags), a_contacts(&contacts);
    const SessionFrame* last_answer = nullptr;
    size_t next = 0;
    for (size_t i = 0; i < n && next < kept.size(); ++i) {
      if (session.frames[i].answered) last_answer = &session.frames[i];
      if (i != kept[next]) continue;
      ++next;
      const SessionFrame& fr = session.frames[i];
      const SessionFrame none;
      const SessionFrame& w = last_answer != nullptr ? *last_answer : none;
      a_t.Add(fr.t);
      pd::Isometry3 X_WD = pd::Isometry3::Identity();
      X_WD.linear() = fr.q_WD.toRotationMatrix();
      X_WD.translation() = fr.p_WD;
      a_dev.AddPose(X_WD);
      a_tool.AddPose(rerendered.frames[i].X_WT);
      for (int k = 0; k < 3; ++k) a_f.Add(w.f_W[k]), a_tau.Add(w.tau_W[k]);
      a_d.Add(w.depth);
      a_c.AddInt(w.contact_count);
      a_rtt.Add(fr.answered ? fr.round_trip_us : -1.0);
      a_ans.AddInt(fr.answered ? 1 : 0);
      a_flags.AddInt(w.flags);
      a_contacts.Sep();
      JsonArray c(&contacts);
      for (const ContactPoint& p : rerendered.frames[i].contacts) {
        for (int k = 0; k < 3; ++k) c.Add(p.p_W[k]);
        for (int k = 0; k < 3; ++k) c.Add(p.n_W[k]);
        c.Add(p.depth);
      }
    }
  }
  double max_force = 0, max_torque = 0;
  size_t max_contacts = 0;
  for (size_t i = 0; i < n; ++i) {
    max_force = std::max(max_force, session.frames[i].f_W.norm());
    max_torque = std::max(max_torque, session.frames[i].tau_W.norm());
    max_contacts = std::max(max_contacts, rerendered.frames[i].contacts.size());
  }
  const RerenderAgreement& ag = rerendered.agreement;
  char note[1024];
  std::snprintf(note, sizeof(note),
                "Arrows: the recorded wrench on the device, the largest (%.3g N, %.3g N·m) "
                "drawn full length, or 5%% of the device limit (%.3g N, %.3g N·m) if more. "
                "The simulated tool and the contacts are not on the wire: they "
                "are recomputed by the server's renderer from the recorded device poses; its "
                "force differs from the recorded one by %.3g N median, %.3g N p99, %.3g N max "
                "over %lld answered poses.",
                max_force, max_torque, config.device.max_force, config.device.max_torque,
                ag.median_force_diff, ag.p99_force_diff, ag.max_force_diff,
                static_cast<long long>(ag.compared));
  j += ",\"t\":" + t + ",\"device\":" + dev + ",\"tool_pose\":" + tool + ",\"force\":" + force +
       ",\"torque\":" + torque + ",\"depth\":" + depth + ",\"contact_count\":" + count +
       ",\"round_trip_us\":" + rtt + ",\"answered\":" + answered + ",\"flags\":" + flags +
       ",\"contacts\":" + contacts + ",\"max_force\":" + std::to_string(max_force) +
       ",\"max_torque\":" + std::to_string(max_torque) +
       ",\"force_limit\":" + std::to_string(config.device.max_force) +
       ",\"torque_limit\":" + std::to_string(config.device.max_torque) +
       ",\"max_contacts_per_frame\":" + std::to_string(max_contacts) + ",\"note\":" + Quoted(note) +
       "}";

  std::string page = kViewerPageTemplate;
  std::string title = "Haptic session: ";
  for (char c : config.name) title += c == '<' ? std::string("&lt;") : c == '&' ? std::string("&amp;") : std::string(1, c);
  Replace(&page, "@TITLE@", title);
  Replace(&page, "@THREE_JS@", three);
  Replace(&page, "@ORBIT_JS@", orbit);
  Replace(&page, "@SESSION_JSON@", j);
  Replace(&page, "@VIEWER_JS@", kViewerScript);
  out << page;
}

}  // namespace probes
