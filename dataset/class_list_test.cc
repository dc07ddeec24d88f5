#include "dataset/class_list.h"

#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "dataset/test_folder.h"

namespace depot::dataset {
namespace {

TEST(ClassList, ADatasetsClassesReadBackInTheirIndexOrder) {
  const std::string dir = testing::new_test_folder();
  const std::vector<std::string> names{"person", "dog", "chair"};
  write_dataset_classes(dir, names);
  EXPECT_EQ(testing::read_text(dir, "classes.txt"), "person\ndog\nchair\n");
  EXPECT_EQ(read_dataset_classes(dir), names);
}

TEST(ClassList, AMissingOrRepeatingListIsOneErrorNamingTheFile) {
  const std::string dir = testing::new_test_folder();
  EXPECT_EQ(error_of([&] { read_dataset_classes(dir); }),
            dir + "/classes.txt: missing (the detectable classes, one a line)");
  testing::write_text(dir, "classes.txt", "person\ndog\nperson\n");
  EXPECT_EQ(error_of([&] { read_dataset_classes(dir); }),
            dir + "/classes.txt: class 'person' is listed twice");
  testing::write_text(dir, "classes.txt", "person\n\ndog\n");
  EXPECT_EQ(error_of([&] { read_dataset_classes(dir); }),
            dir + "/classes.txt:2: blank line before a class name");
}

}  // namespace
}  // namespace depot::dataset
