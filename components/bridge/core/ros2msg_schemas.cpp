#include "bridge/core/ros2msg_schemas.hpp"

#include <map>
#include <set>
#include <sstream>
#include <vector>

namespace ltm::bridge {
namespace {

// ROS 2's definitions (Humble), without comments; the layouts of idl/ follow them field by field.
const std::map<std::string, std::string>& definitions() {
    static const std::map<std::string, std::string> table = {
        {"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"},
        {"builtin_interfaces/Duration", "int32 sec\nuint32 nanosec\n"},
        {"std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
        {"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
        {"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
        {"geometry_msgs/Quaternion", "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n"},
        {"geometry_msgs/Pose", "Point position\nQuaternion orientation\n"},
        {"geometry_msgs/PoseStamped", "std_msgs/Header header\nPose pose\n"},
        {"geometry_msgs/PoseWithCovariance", "Pose pose\nfloat64[36] covariance\n"},
        {"geometry_msgs/PoseWithCovarianceStamped",
         "std_msgs/Header header\nPoseWithCovariance pose\n"},
        {"geometry_msgs/Transform", "Vector3 translation\nQuaternion rotation\n"},
        {"geometry_msgs/TransformStamped",
         "std_msgs/Header header\nstring child_frame_id\nTransform transform\n"},
        {"geometry_msgs/Twist", "Vector3 linear\nVector3 angular\n"},
        {"geometry_msgs/TwistWithCovariance", "Twist twist\nfloat64[36] covariance\n"},
        {"nav_msgs/Odometry",
         "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
         "geometry_msgs/TwistWithCovariance twist\n"},
        {"nav_msgs/Path", "std_msgs/Header header\ngeometry_msgs/PoseStamped[] poses\n"},
        {"tf2_msgs/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"},
        {"sensor_msgs/PointField",
         "uint8 INT8 = 1\nuint8 UINT8 = 2\nuint8 INT16 = 3\nuint8 UINT16 = 4\nuint8 INT32 = 5\n"
         "uint8 UINT32 = 6\nuint8 FLOAT32 = 7\nuint8 FLOAT64 = 8\n"
         "string name\nuint32 offset\nuint8 datatype\nuint32 count\n"},
        {"sensor_msgs/PointCloud2",
         "std_msgs/Header header\nuint32 height\nuint32 width\nPointField[] fields\n"
         "bool is_bigendian\nuint32 point_step\nuint32 row_step\nuint8[] data\nbool is_dense\n"},
        {"sensor_msgs/Imu",
         "std_msgs/Header header\ngeometry_msgs/Quaternion orientation\n"
         "float64[9] orientation_covariance\ngeometry_msgs/Vector3 angular_velocity\n"
         "float64[9] angular_velocity_covariance\ngeometry_msgs/Vector3 linear_acceleration\n"
         "float64[9] linear_acceleration_covariance\n"},
        // Foxglove's scene types in their ROS 2 form (foxglove/schemas, ros_foxglove_msgs/ros2):
        // Foxglove's 3D panel draws foxglove_msgs/msg/SceneUpdate as foxglove.SceneUpdate.
        {"foxglove_msgs/Color", "float64 r\nfloat64 g\nfloat64 b\nfloat64 a\n"},
        {"foxglove_msgs/KeyValuePair", "string key\nstring value\n"},
        {"foxglove_msgs/ArrowPrimitive",
         "geometry_msgs/Pose pose\nfloat64 shaft_length\nfloat64 shaft_diameter\n"
         "float64 head_length\nfloat64 head_diameter\nfoxglove_msgs/Color color\n"},
        {"foxglove_msgs/CubePrimitive",
         "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 size\nfoxglove_msgs/Color color\n"},
        {"foxglove_msgs/SpherePrimitive",
         "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 size\nfoxglove_msgs/Color color\n"},
        {"foxglove_msgs/CylinderPrimitive",
         "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 size\nfloat64 bottom_scale\n"
         "float64 top_scale\nfoxglove_msgs/Color color\n"},
        {"foxglove_msgs/LinePrimitive",
         "uint8 LINE_STRIP=0\nuint8 LINE_LOOP=1\nuint8 LINE_LIST=2\nuint8 type\n"
         "geometry_msgs/Pose pose\nfloat64 thickness\nbool scale_invariant\n"
         "geometry_msgs/Point[] points\nfoxglove_msgs/Color color\nfoxglove_msgs/Color[] colors\n"
         "uint32[] indices\n"},
        {"foxglove_msgs/TriangleListPrimitive",
         "geometry_msgs/Pose pose\ngeometry_msgs/Point[] points\nfoxglove_msgs/Color color\n"
         "foxglove_msgs/Color[] colors\nuint32[] indices\n"},
        {"foxglove_msgs/TextPrimitive",
         "geometry_msgs/Pose pose\nbool billboard\nfloat64 font_size\nbool scale_invariant\n"
         "foxglove_msgs/Color color\nstring text\n"},
        {"foxglove_msgs/ModelPrimitive",
         "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 scale\nfoxglove_msgs/Color color\n"
         "bool override_color\nstring url\nstring media_type\nuint8[] data\n"},
        {"foxglove_msgs/SceneEntity",
         "builtin_interfaces/Time timestamp\nstring frame_id\nstring id\n"
         "builtin_interfaces/Duration lifetime\nbool frame_locked\n"
         "foxglove_msgs/KeyValuePair[] metadata\nfoxglove_msgs/ArrowPrimitive[] arrows\n"
         "foxglove_msgs/CubePrimitive[] cubes\nfoxglove_msgs/SpherePrimitive[] spheres\n"
         "foxglove_msgs/CylinderPrimitive[] cylinders\nfoxglove_msgs/LinePrimitive[] lines\n"
         "foxglove_msgs/TriangleListPrimitive[] triangles\nfoxglove_msgs/TextPrimitive[] texts\n"
         "foxglove_msgs/ModelPrimitive[] models\n"},
        {"foxglove_msgs/SceneEntityDeletion",
         "uint8 MATCHING_ID=0\nuint8 ALL=1\nbuiltin_interfaces/Time timestamp\nuint8 type\n"
         "string id\n"},
        {"foxglove_msgs/SceneUpdate",
         "foxglove_msgs/SceneEntityDeletion[] deletions\nfoxglove_msgs/SceneEntity[] entities\n"},
    };
    return table;
}

bool primitive(const std::string& t) {
    static const std::set<std::string> names = {
        "bool",   "byte",  "char",   "int8",    "uint8",   "int16",  "uint16", "int32",
        "uint32", "int64", "uint64", "float32", "float64", "string", "wstring"};
    return names.count(t) > 0;
}

// "pkg/Type" of a field's type as written in `pkg`'s definition ("Pose" -> "geometry_msgs/Pose").
std::string qualified(const std::string& type, const std::string& pkg) {
    std::string t = type.substr(0, type.find('['));
    if (primitive(t)) return "";
    return t.find('/') == std::string::npos ? pkg + "/" + t : t;
}

// Depth first, each type once, in the order ROS 2's tools list them.
void collect(const std::string& name, std::vector<std::string>& order,
             std::set<std::string>& seen) {
    const std::string pkg = name.substr(0, name.find('/'));
    std::istringstream lines(definitions().at(name));
    std::string line;
    while (std::getline(lines, line)) {
        std::istringstream words(line);
        std::string type, field;
        words >> type >> field;
        if (type.empty() || field.find('=') != std::string::npos) continue;
        const std::string dep = qualified(type, pkg);
        if (dep.empty() || seen.count(dep)) continue;
        seen.insert(dep);
        order.push_back(dep);
        collect(dep, order, seen);
    }
}

}  // namespace

std::string ros2msg_schema(const std::string& ros_name) {
    std::string name = ros_name;
    const std::size_t msg = name.find("/msg/");
    if (msg != std::string::npos) name.replace(msg, 5, "/");
    if (!definitions().count(name)) return "";
    std::vector<std::string> order;
    std::set<std::string> seen{name};
    collect(name, order, seen);
    std::string text = definitions().at(name);
    for (const std::string& dep : order) {
        text += std::string(80, '=') + "\nMSG: " + dep + "\n" + definitions().at(dep);
    }
    return text;
}

}  // namespace ltm::bridge
