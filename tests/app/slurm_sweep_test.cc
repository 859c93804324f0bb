// The Slurm path run, not only documented (label slow): a one-node cluster stood up on this machine
// (scripts/slurm_local_cluster.sh: munged, slurmctld, slurmd on localhost), a small sweep submitted
// through scripts/slurm_sweep.sh as a job array of 2 shards and a dependent merge job, and the merged
// summary checked against the unsharded run's. Skipped without root or without the packages slurm-wlm
// and munge (scripts/setup.sh installs them).
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "run_sortcell.h"
#include "sweep_test_support.h"
#include "temp_dir.h"
#include "source_tree.h"

namespace {

using sortcell_test::kSource;

using sortcell_test::ReadFile;

// Whether a TCP port can be bound on every address, as slurmctld and slurmd bind theirs.
bool PortIsFree(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return false;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  address.sin_port = htons(static_cast<uint16_t>(port));
  const bool free = bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0;
  close(fd);
  return free;
}

// Two neighbouring free ports (slurmctld's, slurmd's), searched from one of this test process's own so
// that a cluster already on this machine, or another run of this test, is left alone.
int FreePortPair() {
  const int first = 20000 + static_cast<int>(getpid() % 20000);
  for (int port = first; port < first + 200; port += 2) {
    if (PortIsFree(port) && PortIsFree(port + 1)) return port;
  }
  return first;  // Then the cluster's start fails, and its log says why.
}

// The cluster, stopped however the test ends.
class LocalCluster {
 public:
  explicit LocalCluster(std::string dir) : dir_(std::move(dir)) {
    const int port = FreePortPair();
    env_ = "SORTCELL_SLURMCTLD_PORT=" + std::to_string(port) + " SORTCELL_SLURMD_PORT=" + std::to_string(port + 1) +
           " SLURM_CONF=" + dir_ + "/slurm.conf ";
    status_ = std::system(
        (env_ + kSource + "/scripts/slurm_local_cluster.sh start " + dir_ + " > " + dir_ + ".log 2>&1").c_str());
  }
  ~LocalCluster() { std::system((kSource + "/scripts/slurm_local_cluster.sh stop " + dir_).c_str()); }
  LocalCluster(const LocalCluster&) = delete;
  LocalCluster& operator=(const LocalCluster&) = delete;

  int exit_code() const { return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1; }
  const std::string& env() const { return env_; }

 private:
  std::string dir_, env_;
  int status_ = -1;
};

TEST(SlurmSweep, AJobArrayOfShardsAndItsMergeGiveTheUnshardedSummary) {
  if (getuid() != 0) GTEST_SKIP() << "slurmd needs root";
  if (std::system("command -v slurmctld > /dev/null && command -v munged > /dev/null") != 0) {
    GTEST_SKIP() << "Slurm is not installed (Debian packages slurm-wlm and munge)";
  }
  const sortcell_test::TempDir dir("slurm");
  const LocalCluster cluster((dir / "cluster").string());
  ASSERT_EQ(cluster.exit_code(), 0) << ReadFile((dir / "cluster").string() + ".log");

  const std::string spec = sortcell_test::SmallSweepSpec(dir / "spec.yaml", 43, 4);
  const std::string out = (dir / "out").string();
  // At most 10 minutes: a job that never leaves the queue fails the test rather than hanging it.
  const std::string submit = cluster.env() + "SORTCELL=" + SORTCELL_BINARY + " SORTCELL_SLURM_WAIT=1 timeout 600 " +
                             kSource + "/scripts/slurm_sweep.sh " + spec + " 2 " + out + " -j 1 > " + out + ".log 2>&1";
  ASSERT_EQ(std::system(submit.c_str()), 0) << ReadFile(out + ".log") << ReadFile(out + "/slurm/merge.log");
  for (const char* shard : {"/shard1/results.jsonl", "/shard2/results.jsonl"}) {
    EXPECT_EQ(sortcell_test::Lines(out + shard).size(), 2u) << shard << ": each shard ran its 2 episodes";
  }
  EXPECT_NE(ReadFile(out + "/slurm/merge.log").find("0 of 4 episodes in this shard run now (4 were already done"),
            std::string::npos)
      << "the merge ran nothing itself: " << ReadFile(out + "/slurm/merge.log");

  const auto unsharded = sortcell_test::RunSortcell("sweep " + spec + " -j 2 --out " + (dir / "whole").string());
  ASSERT_EQ(unsharded.exit_code, 0) << unsharded.err;
  const auto merged = nlohmann::json::parse(ReadFile(out + "/merged/summary.json"));
  const auto whole = nlohmann::json::parse(ReadFile((dir / "whole" / "summary.json").string()));
  EXPECT_EQ(merged["episodes"], 4);
  EXPECT_EQ(sortcell_test::SummaryWithoutMachineFigures(merged), sortcell_test::SummaryWithoutMachineFigures(whole));
}

}  // namespace
