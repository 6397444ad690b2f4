// Runs a shell pipeline with stdout captured apart from stderr, for tests
// of tools that write binary streams (depthkey-shmcat | ffmpeg).
#pragma once

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace depthkey::test {

struct Result {
	int status = -1; // exit status, or -1 if it did not exit normally
	std::string out;
	std::string err;
};

// Runs `command` under bash -o pipefail (so a failing shmcat fails the
// pipeline), capturing stdout; stderr goes through a file so that neither
// pipe can fill up and stall the child.
inline Result runPiped(const std::string &command)
{
	Result result;
	char errPath[] = "/tmp/depthkey-shmcat-test-XXXXXX";
	int errFd = mkstemp(errPath);
	int pipeFds[2];
	if (errFd < 0 || pipe(pipeFds) < 0)
		return result;
	pid_t child = fork();
	if (child == 0) {
		dup2(pipeFds[1], STDOUT_FILENO);
		dup2(errFd, STDERR_FILENO);
		close(pipeFds[0]);
		execl("/bin/bash", "bash", "-o", "pipefail", "-c", command.c_str(), nullptr);
		_exit(127);
	}
	close(pipeFds[1]);
	char buffer[65536];
	ssize_t n;
	while ((n = read(pipeFds[0], buffer, sizeof(buffer))) > 0)
		result.out.append(buffer, static_cast<size_t>(n));
	close(pipeFds[0]);
	int status = 0;
	waitpid(child, &status, 0);
	result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
	std::ifstream errFile(errPath);
	std::stringstream text;
	text << errFile.rdbuf();
	result.err = text.str();
	close(errFd);
	unlink(errPath);
	return result;
}

} // namespace depthkey::test
