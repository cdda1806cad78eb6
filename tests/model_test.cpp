// The performance model's arithmetic (issue 19): counted vector ticks become scalar operations, each class and
// filter is divided by its rate, software devices add the terms and GPUs overlap them, the largest term is the bound.
#include <gtest/gtest.h>

#include "model/model.h"

namespace {
using namespace shadetwin::model;

DeviceDesc device(bool overlap) {
  DeviceDesc d;
  d.opsPerSecond.fill(1e9);
  d.opsPerSecond[kIAlu] = 2e9;
  d.lookupsPerSecond = {4e8, 2e8, 1e8};
  d.bandwidthBytesPerSecond = 1e10;
  d.dispatchSeconds = 1e-4;
  d.unitsOverlap = overlap;
  return d;
}

TEST(Model, TicksAreEightLaneVectorsAndMaskLogicIsIntegerAlu) {
  PassCounts c;
  c.ticks[opcount::kFAdd] = 10;
  c.ticks[opcount::kMaskOp] = 3;
  c.ticks[opcount::kIAlu] = 2;
  const auto ops = scalarOps(c);
  EXPECT_EQ(ops[kFAdd], 80.0);
  EXPECT_EQ(ops[kIAlu], 40.0);
  EXPECT_EQ(ops[kFMul], 0.0);
}

TEST(Model, SoftwareDevicesAddTheTermsGpusOverlapThem) {
  PassCounts c;
  c.ticks[opcount::kFMul] = 125000;          // 1e6 scalar fmul: 1 ms at 1e9/s
  c.ticks[opcount::kIAlu] = 250000;          // 2e6 integer ops: 1 ms at 2e9/s
  c.ticks[opcount::kTexTrilinear] = 300000;  // 3 ms at 1e8/s
  c.ticks[opcount::kTexNearest] = 400000;    // 1 ms at 4e8/s
  c.bytesRead = 10000000, c.bytesWritten = 5000000;  // 1.5 ms at 1e10 B/s
  const Prediction s = predict(c, device(false));
  EXPECT_DOUBLE_EQ(s.aluSeconds, 2e-3);
  EXPECT_DOUBLE_EQ(s.textureSeconds, 4e-3);
  EXPECT_DOUBLE_EQ(s.memorySeconds, 1.5e-3);
  EXPECT_DOUBLE_EQ(s.seconds, 2e-3 + 4e-3 + 1.5e-3 + 1e-4);
  EXPECT_EQ(s.bound, "texture");
  const Prediction g = predict(c, device(true));
  EXPECT_DOUBLE_EQ(g.seconds, 4e-3 + 1e-4);
  EXPECT_EQ(g.bound, "texture");
  PassCounts idle;  // nothing to do: the launch bounds it
  EXPECT_EQ(predict(idle, device(true)).bound, "launch");
}

}  // namespace
