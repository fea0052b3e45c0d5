#include "maintenance/core/segmentation.hpp"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <limits>

namespace ltm::maintenance {

Segmentation euclidean_segments(const SegmentationConfig& config,
                                const std::vector<Eigen::Vector3f>& points) {
    Segmentation out;
    out.label.assign(points.size(), 0);
    if (points.empty()) return out;
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
    cloud->reserve(points.size());
    for (const Eigen::Vector3f& p : points) cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
    tree->setInputCloud(cloud);
    std::vector<pcl::PointIndices> clusters;
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
    ec.setClusterTolerance(config.tolerance);
    ec.setMinClusterSize(std::max(1, config.min_voxels));
    ec.setMaxClusterSize(std::numeric_limits<int>::max());
    ec.setSearchMethod(tree);
    ec.setInputCloud(cloud);
    ec.extract(clusters);
    for (const pcl::PointIndices& c : clusters) {
        ++out.segments;
        for (int i : c.indices) out.label[std::size_t(i)] = out.segments;
    }
    return out;
}

}  // namespace ltm::maintenance
