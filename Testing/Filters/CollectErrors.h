// SPDX-License-Identifier: BSD-3-Clause
// Collecting what VTK objects report (errors, warnings) in the filter tests.
#pragma once

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkWeakPointer.h"

#include <string>
#include <utility>
#include <vector>

namespace volrad::test {

/// Appends the messages of the events it observes (vtkCommand::ErrorEvent,
/// WarningEvent) to `text`, until it goes (then it stops observing). Not
/// copied or moved: the command points at it.
struct MessageCollector
{
  std::string text;
  vtkNew<vtkCallbackCommand> command;
  std::vector<std::pair<vtkWeakPointer<vtkObject>, unsigned long>> observed;

  MessageCollector()
  {
    command->SetClientData(&text);
    command->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
      *static_cast<std::string*>(self) += static_cast<const char*>(data);
    });
  }
  ~MessageCollector()
  {
    for (auto& [object, tag] : observed) {
      if (object) {
        object->RemoveObserver(tag);
      }
    }
  }
  MessageCollector(const MessageCollector&) = delete;
  MessageCollector& operator=(const MessageCollector&) = delete;

  void observe(vtkObject* object, unsigned long event = vtkCommand::ErrorEvent)
  {
    observed.emplace_back(object, object->AddObserver(event, command));
  }
};

/// Updates the algorithm; returns the error messages it and its executive gave.
inline std::string updateCollectingErrors(vtkAlgorithm* f)
{
  MessageCollector errors;
  errors.observe(f);
  errors.observe(f->GetExecutive());
  f->Update();
  return errors.text;
}

} // namespace volrad::test
