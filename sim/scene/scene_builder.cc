#include "sim/scene/scene_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include <map>
#include <memory>

#include "common/config_path.h"
#include "common/error.h"
#include "common/rng.h"
#include "sim/actors/animal.h"
#include "sim/actors/door.h"
#include "sim/actors/human.h"
#include "sim/actors/limb.h"
#include "sim/assets/asset_catalog.h"
#include "sim/scene/depot_objects.h"
#include "sim/scene/geometry.h"
#include "sim/scene/mesh_props.h"
#include "sim/scene/mjcf_text.h"
#include "sim/scene/skinned_actor_xml.h"
#include "sim/scene/textures.h"

namespace depot::sim {

const char* instance_kind_name(InstanceKind k) {
  switch (k) {
    case InstanceKind::kStructure:
      return "structure";
    case InstanceKind::kStatic:
      return "static";
    case InstanceKind::kPushable:
      return "pushable";
    case InstanceKind::kActor:
      return "actor";
  }
  return "static";
}

namespace {

const char* shape_name(Shape s) {
  switch (s) {
    case Shape::kBox:
      return "box";
    case Shape::kSphere:
      return "sphere";
    case Shape::kCapsule:
      return "capsule";
    case Shape::kEllipsoid:
      return "ellipsoid";
    case Shape::kCylinder:
      return "cylinder";
  }
  return "box";
}

void write_geom(std::ostringstream& x, const GeomDesc& g) {
  x << "<geom type=\"" << shape_name(g.shape) << "\" size=\"";
  switch (g.shape) {
    case Shape::kSphere:
      x << num(g.size.x());
      break;
    case Shape::kCapsule:
    case Shape::kCylinder:
      x << num(g.size.x()) << " " << num(g.size.y());
      break;
    default:
      x << vec(g.size);
  }
  x << "\" pos=\"" << vec(g.local.translation()) << "\" quat=\"" << quat(g.local.linear()) << "\"";
  x << " contype=\"" << g.contype << "\" conaffinity=\"" << g.conaffinity << "\"";
  x << " friction=\"" << num(g.friction) << " 0.005 0.0001\" density=\"" << num(g.density) << "\"";
  if (!g.visible) {
    x << " group=\"3\" rgba=\"0 0 0 0\"";
  } else if (!g.material.empty()) {
    x << " material=\"" << g.material << "\"";
  }
  x << "/>\n";
}

// A body's primitive geoms; with mesh props, those a catalogue mesh replaces
// stay for physics but are hidden (group 3, alpha 0: neither the colour nor
// the segmentation pass draws them).
void write_geoms(std::ostringstream& x, const std::vector<GeomDesc>& geoms, bool drawn_as_mesh) {
  for (GeomDesc g : geoms) {
    if (drawn_as_mesh && g.replaced_by_mesh) g.visible = false;
    write_geom(x, g);
  }
}

// Static bodies and the world's planes.
void write_hall(std::ostringstream& x, const SceneLayout& l) {
  const double hx = l.length / 2, hy = l.width / 2, h = l.height;
  x << "<geom name=\"floor\" type=\"plane\" size=\"" << num(hx) << " " << num(hy)
    << " 0.5\" material=\"floor\" contype=\"1\" conaffinity=\"1\" friction=\"0.05 0.005 "
       "0.0001\"/>\n";
  struct Wall {
    Eigen::Vector3d pos, xaxis;
    double half_width;
  };
  const Wall walls[] = {{{0, hy, h / 2}, {1, 0, 0}, hx},
                        {{0, -hy, h / 2}, {-1, 0, 0}, hx},
                        {{hx, 0, h / 2}, {0, -1, 0}, hy},
                        {{-hx, 0, h / 2}, {0, 1, 0}, hy}};
  for (const auto& w : walls) {
    x << "<geom type=\"plane\" size=\"" << num(w.half_width) << " " << num(h / 2) << " 0.5\" pos=\""
      << vec(w.pos) << "\" xyaxes=\"" << vec(w.xaxis)
      << " 0 0 1\" material=\"wall\" contype=\"0\" conaffinity=\"0\"/>\n";
  }
  x << "<geom type=\"plane\" size=\"" << num(hx) << " " << num(hy) << " 0.5\" pos=\"0 0 " << num(h)
    << "\" xyaxes=\"1 0 0 0 -1 0\" material=\"ceiling\" contype=\"0\" conaffinity=\"0\"/>\n";
}

std::string png_bytes(const cv::Mat& bgr) {
  std::vector<uchar> buf;
  // Stored (level 0): the bytes go straight to MuJoCo's decoder in memory.
  cv::imencode(".png", bgr, buf, {cv::IMWRITE_PNG_COMPRESSION, 0});
  return std::string(buf.begin(), buf.end());
}

// A pusher must start with its push plate clear of its chair or cart, at the
// largest size its appearance can give: a plate inside the target at t = 0
// flings it away while physics settles, before the first frame. `solid` is
// the target's collision geometry's bounds (a mesh chair's extent is larger:
// its mesh has no contacts).
void check_pusher_start(const ActorSpec& a, const Instance& target,
                        const Eigen::AlignedBox3d& solid, const std::string& where) {
  const Path2D path = actor_path(a);
  const double s = a.size * HumanActor::kLargestScale;
  const Eigen::Vector3d centre = HumanActor::push_plate_centre(s);
  const Eigen::Vector3d half = HumanActor::push_plate_half(s);
  Eigen::AlignedBox3d body = solid;
  constexpr double kGap = 0.02;  // m
  body.min() -= Eigen::Vector3d::Constant(kGap);
  body.max() += Eigen::Vector3d::Constant(kGap);
  // Whether the plate overlaps the target with the pusher `back` metres
  // behind its start.
  auto overlaps = [&](double back) {
    const Eigen::Vector2d xy = path.position(a.start_offset) - back * path.tangent(a.start_offset);
    const Pose target_from_root =
        target.pose.inverse() * ground_pose(xy, 0.0, path.heading(a.start_offset));
    Eigen::AlignedBox3d plate;
    for (int i = 0; i < 8; ++i)
      plate.extend(target_from_root * Eigen::Vector3d(centre.x() + (i & 1 ? half.x() : -half.x()),
                                                      centre.y() + (i & 2 ? half.y() : -half.y()),
                                                      centre.z() + (i & 4 ? half.z() : -half.z())));
    return plate.intersects(body);
  };
  if (!overlaps(0.0)) return;
  double back = 0.05;
  while (back < 3.0 && overlaps(back)) back += 0.05;
  fail(where, "actor '" + a.name + "' starts with its hands inside '" + target.name +
                  "' (at its largest size): start its path at least " +
                  fmt::format("{:.2f}", back) + " m further behind it");
}

// Skinned variants of the asset catalogue (people and animals), each loaded
// and encoded once per scene however many actors wear it.
class MeshVariants {
 public:
  explicit MeshVariants(LazyAssetCatalog& catalog) : catalog_(catalog) {}

  struct Variant {
    std::string asset;  // the catalogue entry
    std::string prefix;
    std::shared_ptr<const HumanRig> human;  // a person's rig, or
    std::shared_ptr<const ClipRig> animal;  // an animal's
    SkinMaterials materials;
    const AssetModel& model() const { return human ? human->model() : animal->model(); }
    const std::vector<int>& body_bones() const {
      return human ? human->body_bones() : animal->body_bones();
    }
  };

  // The variant an actor of `class_name` wears, or nullptr when no asset
  // plays that class: drawn by its appearance seed, moved on to the next
  // variant no actor of the scene wears yet while there is one (so three
  // people are three different people). Actors are dressed in file order, so
  // the same scenario and seed always dress the same actors.
  const Variant* pick(const std::string& class_name, uint64_t appearance) {
    const std::vector<const CatalogAsset*> assets =
        catalog_assets_of_class(catalog_.get(), class_name);
    if (assets.empty()) return nullptr;
    size_t i = Rng(derive_seed(appearance, 0x6d657368)).below(assets.size());
    for (size_t k = 0; k < assets.size(); ++k) {
      const size_t j = (i + k) % assets.size();
      if (!variants_.count(assets[j]->name)) {
        i = j;
        break;
      }
    }
    const CatalogAsset& entry = *assets[i];
    auto it = variants_.find(entry.name);
    if (it != variants_.end()) return &it->second;
    Variant v;
    v.asset = entry.name;
    v.prefix = class_name + "_" + entry.name;
    auto model = std::make_shared<const AssetModel>(load_catalog_asset(catalog_.get(), entry));
    if (class_name == "person")
      v.human = std::make_shared<const HumanRig>(model);
    else
      v.animal = std::make_shared<const ClipRig>(
          model, entry, class_name == "bird" ? ClipRig::Gait::kFly : ClipRig::Gait::kWalk);
    v.materials = encode_skin_materials(*model, v.prefix);
    return &variants_.emplace(entry.name, std::move(v)).first->second;
  }
  const std::map<std::string, Variant>& used() const { return variants_; }

 private:
  LazyAssetCatalog& catalog_;
  std::map<std::string, Variant> variants_;
};

}  // namespace

SceneModel build_scene(const SceneLayout& layout, const ClassTable& classes,
                       const Scenario& scenario, const CameraIntrinsics& render_camera) {
  SceneModel model;
  const CameraIntrinsics& cam = render_camera;
  std::ostringstream x;
  x << "<mujoco model=\"depot\">\n<compiler angle=\"radian\"/>\n<option timestep=\"0.004\"/>\n";
  x << "<visual>\n<global offwidth=\"" << cam.width << "\" offheight=\"" << cam.height << "\"/>\n"
    << "<quality offsamples=\"0\" numslices=\"16\" numstacks=\"8\" numquads=\"1\" shadowsize=\""
    << (scenario.shadows ? 2048 : 0) << "\"/>\n"
    << "<headlight ambient=\"0.32 0.32 0.32\" diffuse=\"0 0 0\" specular=\"0 0 0\"/>\n"
    << "<map znear=\"0.005\" zfar=\"3\"/>\n</visual>\n";
  x << "<statistic extent=\"10\" center=\"0 0 1\"/>\n";

  // Textures and materials, in memory.
  TextureSet textures = make_depot_textures(scenario.world_seed());
  x << "<asset>\n";
  for (const auto& t : textures.textures) {
    std::string file = "tex_" + t.name + ".png";
    model.assets.emplace_back(file, png_bytes(t.bgr));
    x << "<texture name=\"" << t.name << "\" type=\"" << (t.cube ? "cube" : "2d") << "\" file=\""
      << file << "\"/>\n";
  }
  for (MaterialSpec m : textures.materials) {
    // The layout's paint: its tints multiply the hall's wall and floor colour.
    const Eigen::Vector3d* tint = m.name == "wall"    ? &layout.wall_tint
                                  : m.name == "floor" ? &layout.floor_tint
                                                      : nullptr;
    if (tint)
      for (int k = 0; k < 3; ++k) m.rgba[k] *= (*tint)[k];
    x << "<material name=\"" << m.name << "\"";
    if (!m.texture.empty()) {
      x << " texture=\"" << m.texture << "\" texrepeat=\"" << num(m.texrepeat) << " "
        << num(m.texrepeat) << "\" texuniform=\"true\"";
    }
    x << " rgba=\"" << num(m.rgba[0]) << " " << num(m.rgba[1]) << " " << num(m.rgba[2]) << " "
      << num(m.rgba[3]) << "\" specular=\"0\" shininess=\"0\" reflectance=\"0\"/>\n";
  }
  x << "</asset>\n<worldbody>\n";
  for (const SceneLight& l : layout.lights) {
    x << "<light pos=\"" << vec(l.position) << "\" dir=\"0 0 -1\" directional=\"false\" diffuse=\""
      << vec(l.colour) << "\""
      << " specular=\"0 0 0\" attenuation=\"1 0.02 0\" cutoff=\"80\" exponent=\"1\" castshadow=\""
      << (scenario.shadows ? "true" : "false") << "\"/>\n";
  }

  auto add_instance = [&](const std::string& name, const std::string& class_name, InstanceKind kind,
                          const std::string& context) -> Instance& {
    const ObjectClass& c = classes.get(class_name, context);
    Instance inst;
    if (model.instances.size() >= 65534) fail(context, "too many instances");
    inst.id = static_cast<uint16_t>(model.instances.size() + 1);
    inst.name = name;
    inst.class_name = c.name;
    inst.category = c.category;
    inst.kind = kind;
    model.instances.push_back(inst);
    return model.instances.back();
  };

  // 1: the hall itself (world body).
  write_hall(x, layout);
  {
    Instance& hall = add_instance("hall", "structure", InstanceKind::kStructure, layout.path);
    hall.bodies.push_back("world");
    hall.extent =
        Eigen::AlignedBox3d(Eigen::Vector3d(-layout.length / 2, -layout.width / 2, 0),
                            Eigen::Vector3d(layout.length / 2, layout.width / 2, layout.height));
  }

  // Furniture props as catalogue meshes (props_style: mesh): desks here,
  // chairs among the pushables; each model loaded and encoded once.
  const bool mesh_props = scenario.props_style == "mesh";
  LazyAssetCatalog catalog(classes, scenario.asset_catalog_path);
  MeshProps props(catalog);

  // Static furniture: one fixed body per instance.
  for (const SceneObject& object : layout.objects) {
    for (const InstanceGeometry& g : build_scene_object(object, scenario.world_seed())) {
      const std::string context = layout.path + ": object '" + object.name + "'";
      Instance& inst = add_instance(g.name, g.class_name, InstanceKind::kStatic, context);
      const std::string body = "static/" + g.name;
      inst.bodies.push_back(body);
      inst.pose = g.pose;
      inst.extent = local_bounds(g.geoms);
      PropGeoms mesh;
      const bool desk_mesh =
          mesh_props && object.type == "desk" && g.class_name == "desk" && props.has_model("desk");
      if (desk_mesh) {
        mesh = props.desk(object, context);
        inst.extent.extend(mesh.bounds);
        inst.asset = mesh.asset;
      }
      x << "<body name=\"" << body << "\" pos=\"" << vec(g.pose.translation()) << "\" quat=\""
        << quat(g.pose.linear()) << "\">\n";
      write_geoms(x, g.geoms, desk_mesh);
      x << mesh.xml << "</body>\n";
    }
  }

  // Pushables: free bodies.
  std::string props_assets;  // <asset> section of the mesh props, after the bodies
  std::map<std::string, Eigen::AlignedBox3d> pushable_solids;  // collision geoms' bounds
  const std::string where = scenario.source_path;
  for (const ActorSpec& a : scenario.actors) {
    if (!is_pushable_actor(a.type)) continue;
    if (!layout.contains(a.position, 0.3))
      fail(where, "actor '" + a.name + "' is outside the hall");
    InstanceGeometry g =
        build_pushable(a.type, a.name, derive_seed(scenario.world_seed(), a.appearance));
    Instance& inst =
        add_instance(a.name, a.type, InstanceKind::kPushable, where + ": actor '" + a.name + "'");
    const std::string body = "pushable/" + a.name;
    inst.bodies.push_back(body);
    inst.pose = ground_pose(a.position, 0.0, deg(a.yaw_deg));
    inst.extent = local_bounds(g.geoms);
    pushable_solids[a.name] = inst.extent;
    PropGeoms mesh;
    const bool chair_mesh = mesh_props && a.type == "chair" && props.has_model("chair");
    if (chair_mesh) {
      mesh = props.chair();
      inst.extent.extend(mesh.bounds);
      inst.asset = mesh.asset;
    }
    x << "<body name=\"" << body << "\" pos=\"" << vec(inst.pose.translation()) << "\" quat=\""
      << quat(inst.pose.linear()) << "\">\n<freejoint/>\n";
    write_geoms(x, g.geoms, chair_mesh);
    x << mesh.xml << "</body>\n";
  }
  if (!props.empty()) {
    // The props' materials and meshes, shared by every instance.
    props_assets = "<asset>\n" + props.asset_xml() + "</asset>\n";
    props.append_files(model.assets);
  }

  // Animated actors: one mocap body per part.
  std::vector<std::pair<std::string, std::string>> plate_welds;  // plate body, mocap target
  std::vector<std::string> pending_plates;
  const bool mesh_style = scenario.actors_style == "mesh";
  MeshVariants variants(catalog);
  std::string skins;  // <skin> elements, written in a second <asset> section
  // One animated instance: a mocap body per part (geoms unless a skinned
  // model draws it), the push plate, and the skinned model's bone bodies.
  auto add_animated = [&](std::unique_ptr<Actor> actor, const MeshVariants::Variant* variant) {
    const std::string name = actor->name();
    Instance& inst = add_instance(name, actor->class_name(), InstanceKind::kActor,
                                  where + ": actor '" + name + "'");
    inst.actor = static_cast<int>(model.actors.size());
    if (variant) inst.asset = variant->asset;
    inst.pose = actor->root_pose(0.0);
    inst.extent = actor->local_extent();
    std::vector<Pose> poses;
    actor->pose_parts(0.0, poses);
    for (size_t i = 0; i < actor->parts().size(); ++i) {
      const BodyPart& part = actor->parts()[i];
      const std::string body = "actor/" + name + "/" + part.name;
      inst.bodies.push_back(body);
      GeomDesc g;
      g.shape = part.shape;
      g.size = part.size;
      g.material = part.material;
      g.contype = 0;
      g.conaffinity = 0;
      x << "<body name=\"" << body << "\" mocap=\"true\" pos=\"" << vec(poses[i].translation())
        << "\" quat=\"" << quat(poses[i].linear()) << "\">\n";
      // A skinned actor keeps its parts' mocap bodies without geoms.
      if (!part.pusher && !variant) write_geom(x, g);
      x << "</body>\n";
      if (part.pusher) {
        // The push plate is a free body welded to its mocap target: it has a
        // real velocity, so contacts push chairs and carts instead of the
        // plate tunnelling into them.
        const std::string plate = body + "_plate";
        plate_welds.emplace_back(plate, body);
        g.visible = false;
        g.contype = kCollidePusher;
        g.density = 300.0;
        x << "<body name=\"" << plate << "\" pos=\"" << vec(poses[i].translation()) << "\" quat=\""
          << quat(poses[i].linear()) << "\">\n<freejoint/>\n";
        write_geom(x, g);
        x << "</body>\n";
        pending_plates.push_back(plate);
      }
    }
    for (auto& plate : pending_plates) inst.bodies.push_back(plate);
    pending_plates.clear();
    if (variant) {
      // Bone bodies come after the parts: World poses them in this order.
      actor->pose_bones(0.0, poses);
      std::vector<std::string> bones;
      x << bone_bodies_xml(variant->model(), variant->body_bones(), poses,
                           "actor/" + name + "/bone", bones);
      skins += skins_xml(variant->model(), variant->body_bones(), actor->mesh_scale(),
                         variant->materials.material_names, bones, "actor/" + name, inst.skins);
      for (auto& b : bones) inst.bodies.push_back(b);
    }
    model.actors.push_back(std::move(actor));
  };
  for (const ActorSpec& a : scenario.actors) {
    if (!is_living_actor(a.type) && !is_vehicle_actor(a.type)) continue;
    for (const auto& p : a.path)
      if (!layout.contains(p, 0.2))
        fail(where, "actor '" + a.name + "' has a path point outside the hall");
    SeatPose seat;
    const SeatPose* seat_ptr = nullptr;
    if (a.action == "sit") {
      for (const ActorSpec& c : scenario.actors)
        if (c.name == a.target) {
          seat.position = c.position;
          seat.yaw = deg(c.yaw_deg);
          seat.seat_height = kChairSeatHeight;
        }
      seat_ptr = &seat;
    }
    if (a.action == "push") {
      for (const Instance& target : model.instances)
        if (target.kind == InstanceKind::kPushable && target.name == a.target)
          check_pusher_start(a, target, pushable_solids.at(target.name), where);
    }
    std::unique_ptr<Actor> actor = make_actor(a, seat_ptr);
    const MeshVariants::Variant* variant =
        mesh_style ? variants.pick(actor->class_name(), a.appearance) : nullptr;
    if (variant) {
      if (auto* human = dynamic_cast<HumanActor*>(actor.get())) human->use_mesh(variant->human);
      if (auto* animal = dynamic_cast<QuadrupedActor*>(actor.get()))
        animal->use_mesh(variant->animal);
      if (auto* bird = dynamic_cast<BirdActor*>(actor.get())) bird->use_mesh(variant->animal);
    }
    // A carrier's goods are an instance of their own class (crate, sack, pallet).
    std::unique_ptr<Actor> goods = actor->make_carried_goods();
    add_animated(std::move(actor), variant);
    if (goods) add_animated(std::move(goods), nullptr);
  }
  // Doors that swing open and shut: animated leaves.
  for (const DoorSpec& d : scenario.doors)
    add_animated(std::make_unique<DoorActor>(d, scenario.world_seed()), nullptr);

  // The RGB-D camera rides a mocap body; MuJoCo cameras look along -z.
  const double fovy = 2.0 * std::atan(cam.height / 2.0 / cam.f) * 180.0 / M_PI;
  x << "<body name=\"" << model.camera_body << "\" mocap=\"true\" pos=\"0 0 1\">\n<camera name=\""
    << model.camera_name << "\" fovy=\"" << num(fovy) << "\"/>\n</body>\n";
  x << "</worldbody>\n" << props_assets;
  if (!skins.empty()) {
    x << "<asset>\n";
    for (const auto& [index, v] : variants.used()) {
      x << v.materials.asset_xml;
      for (const auto& f : v.materials.files) model.assets.push_back(f);
    }
    x << skins << "</asset>\n";
  }
  if (!plate_welds.empty()) {
    x << "<equality>\n";
    for (const auto& [plate, target] : plate_welds)
      x << "<weld body1=\"" << plate << "\" body2=\"" << target << "\" solref=\"0.02 1\"/>\n";
    x << "</equality>\n";
  }
  // MuJoCo's stack (its broad phase pairs bodies): a crowd of skinned people
  // has thousands of bodies, beyond what MuJoCo sizes for few dofs.
  size_t bodies = 0;
  for (const Instance& inst : model.instances) bodies += inst.bodies.size();
  // (At most 2^27 mjtNums, 1 GB: far beyond any shipped scene.)
  x << "<size nstack=\"" << std::min<size_t>(1000000 + bodies * bodies / 2, size_t{1} << 27)
    << "\"/>\n";
  x << "</mujoco>\n";
  model.xml = x.str();
  return model;
}

}  // namespace depot::sim
